// The technique pyramid with merges (issue 32): under `--integrator vcm` each length k >= 2 has a
// row of merges M(s, k + 2 - s) under its connections; a click on a merge's thumbnail isolates that
// merge as the command line's --isolate MS,T does, and the arrow keys move among the merges.
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <string>

namespace {

const std::string kPyramidTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_pyramid";
const std::string kPyramidBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";
// 800 x 500 with the pyramid of length 3: M(2,2) is the thumbnail under (2,1), at (697, 213).
const std::string kPyramidRun =
    " --width 800 --height 500 --render-scale 0.25 --spp 2 --threads 2 --force --headless --frames 34 --integrator vcm "
    "--noncaustic-photons 1 ";  // every light vertex: each merge's own image in 2 spp
constexpr int kM22X = 697, kM22Y = 213;

pathlab::test::CommandRun runPyramidView(const std::string& args) {
  return pathlab::test::runPathlab(kPyramidTmp, "view " + kPyramidBox + kPyramidRun + args);
}

TEST(ViewerPyramid, AClickOnAMergeIsolatesItAndArrowsMoveAmongMerges) {
  const std::string clicked = kPyramidTmp + "/clicked.png", moved = kPyramidTmp + "/moved.png";
  const std::string m22 = kPyramidTmp + "/m22.png", m23 = kPyramidTmp + "/m23.png", all = kPyramidTmp + "/all.png";
  // The panel's "unweighted" box (each merge's own estimate of its length: M(2,2) and M(2,3) are
  // different images), then the thumbnail. A click holds the button down for two frames, when
  // ImGui keeps the keys; Tab hides the panels so that the image has the size of a --hide-ui run's.
  const std::string click =
      "'4:wait=2;5:click=598,39;10:click=" + std::to_string(kM22X) + "," + std::to_string(kM22Y);
  pathlab::test::CommandRun r = runPyramidView("--pyramid 3 --script " + click + ";16:key=Tab' --screenshot " + clicked);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // Up: t + 1, the merge M(2,3) (the connection (2,3) would be another image).
  r = runPyramidView("--pyramid 3 --script " + click + ";16:key=Up;18:key=Tab' --screenshot " + moved);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  for (const auto& [isolate, out] : {std::pair{"M2,2", m22}, std::pair{"M2,3", m23}}) {
    r = runPyramidView(std::string("--hide-ui --unweighted --isolate ") + isolate + " --screenshot " + out);
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  r = runPyramidView("--hide-ui --screenshot " + all);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const pathlab::test::Png a = pathlab::test::readPng(clicked), b = pathlab::test::readPng(moved),
                           c = pathlab::test::readPng(m22), d = pathlab::test::readPng(m23),
                           e = pathlab::test::readPng(all);
  EXPECT_LT(a.meanDifference(c, 0, 0, 800, 500), 1.0);  // the click is --isolate M2,2 --unweighted
  EXPECT_LT(b.meanDifference(d, 0, 0, 800, 500), 1.0);  // Up from it is --isolate M2,3
  EXPECT_GT(a.meanDifference(e, 0, 0, 800, 500), 2.0);  // ... and neither is the combined image
  EXPECT_GT(b.meanDifference(c, 0, 0, 800, 500), 2.0);
}

}  // namespace
