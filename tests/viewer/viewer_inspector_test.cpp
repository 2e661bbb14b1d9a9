// The path inspector end to end (issue 12): headless, K then a click on the Cornell box draws the
// picked sample's subpaths and connections over the image in their colours (camera subpath blue,
// light subpath orange, connections green), none without the click; N steps to the next sample and
// the drawing changes; the render is never restarted by it (the same samples per pixel arrive).
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <regex>
#include <string>

namespace {

using pathlab::test::Png;
using pathlab::test::readPng;

const std::string kInspectorTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_inspector";
const std::string kInspectorBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

// Pixels of the image area (x >= 470 in a 1280 x 720 window with the side panel) within a small
// distance of a colour.
int pixelsNear(const Png& png, int r, int g, int b) {
  int n = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 470; x < png.width; ++x) {
      const int dr = png.rgb[png.index(x, y, 0)] - r, dg = png.rgb[png.index(x, y, 1)] - g,
                db = png.rgb[png.index(x, y, 2)] - b;
      n += dr * dr + dg * dg + db * db < 30 * 30 ? 1 : 0;
    }
  return n;
}

Png view(const std::string& name, const std::string& script) {
  const std::string out = kInspectorTmp + "/" + name + ".png";
  const pathlab::test::CommandRun r = pathlab::test::runPathlab(
      kInspectorTmp, "view " + kInspectorBox + " --headless --width 1280 --height 720 --render-scale 0.25 --max-length 4 --spp 2 "
                "--threads 2 --frames 16 --force --script '" + script + "' --screenshot " + out);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("at 2 spp"), std::string::npos) << r.err;  // the render ran on undisturbed
  return readPng(out);
}

TEST(ViewerInspector, AClickDrawsTheSamplesPathsAndNextSampleChangesThem) {
  const Png none = view("none", "2:key=K;6:wait=2");
  const Png picked = view("picked", "2:key=K;6:wait=2;8:click=760,330");
  const Png next = view("next", "2:key=K;6:wait=2;8:click=760,330;13:key=N");
  ASSERT_GT(picked.width, 0);
  // Camera subpath (90,200,255), light subpath (255,165,60), connections (120,240,120).
  const int blue = pixelsNear(picked, 90, 200, 255), orange = pixelsNear(picked, 255, 165, 60),
            green = pixelsNear(picked, 120, 240, 120);
  EXPECT_GT(blue + orange + green, 300) << blue << " " << orange << " " << green;
  EXPECT_LT(pixelsNear(none, 90, 200, 255) + pixelsNear(none, 255, 165, 60) + pixelsNear(none, 120, 240, 120), 30);
  // The next sample's paths are others.
  EXPECT_GT(picked.meanDifference(next, 470, 0, 1280, 720), 0.2);
}

}  // namespace
