// Vertex merging's controls in the estimator section (issue 32): while the set has merges the
// panel shows the radius, its schedule and the ppm merge site; ticking "ppm" makes the image the
// command line's --integrator ppm (whose site the integrator's radio cannot show: it says bpt).
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <string>

namespace {

const std::string kMergeControlsTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_merge_controls";
const std::string kMergeControlsScene = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf";
// 800 x 700: the ppm box is at (18, 560) under the radius sliders.
const std::string kMergeControlsRun =
    " --width 800 --height 700 --render-scale 0.25 --spp 2 --threads 2 --force --headless --frames 30 ";

pathlab::test::CommandRun runMergeControlsView(const std::string& args) {
  return pathlab::test::runPathlab(kMergeControlsTmp, "view " + kMergeControlsScene + kMergeControlsRun + args);
}

TEST(ViewerMergeControls, TickingPpmMergesOnlyAtTheFirstNonSpecularVertex) {
  const std::string ticked = kMergeControlsTmp + "/ticked.png", ppm = kMergeControlsTmp + "/ppm.png",
                    every = kMergeControlsTmp + "/every.png";
  // PPM's technique set merging everywhere, then the box ticked; Tab hides the panels so that
  // the image has a --hide-ui run's size.
  pathlab::test::CommandRun r = runMergeControlsView(
      "--techniques 's=0;m=all' --script '4:wait=2;5:click=18,585;12:key=Tab' --screenshot " + ticked);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runMergeControlsView("--hide-ui --integrator ppm --screenshot " + ppm);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runMergeControlsView("--hide-ui --techniques 's=0;m=all' --screenshot " + every);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const pathlab::test::Png a = pathlab::test::readPng(ticked), b = pathlab::test::readPng(ppm),
                           c = pathlab::test::readPng(every);
  EXPECT_LT(a.meanDifference(b, 0, 0, 800, 700), 1.0);  // the ticked box is --integrator ppm
  EXPECT_GT(b.meanDifference(c, 0, 0, 800, 700), 2.0);  // ... which merging everywhere is not
}

}  // namespace
