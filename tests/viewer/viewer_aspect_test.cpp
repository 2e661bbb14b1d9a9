// The image keeps the scene camera's aspect ratio whatever room the panels leave (issue 14): in a
// headless screenshot the image region is the camera's shape within a pixel, centred, with bars of
// the background colour, at several window sizes with the panels open and closed. The region comes
// from the closing line ("image WxH+X+Y") and is checked against the screenshot's pixels.
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

namespace {

using pathlab::test::Png;
using pathlab::test::readPng;

const std::string kAspectTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_aspect";

struct AspectCase {
  std::string name;
  std::string scene;  // under assets/
  float aspect;       // its camera's aspectRatio
  int width, height;  // the window
  std::string flags;
  bool panels;        // false: the room is the whole window
};

std::ostream& operator<<(std::ostream& out, const AspectCase& c) { return out << c.name; }

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;
};

// glClearColor(0.08, 0.08, 0.09) in 8 bits (ui/run_viewer.cpp).
bool isBackground(const Png& png, int x, int y) {
  const int r = png.rgb[png.index(x, y, 0)], g = png.rgb[png.index(x, y, 1)], b = png.rgb[png.index(x, y, 2)];
  return std::abs(r - 20) <= 1 && std::abs(g - 20) <= 1 && std::abs(b - 23) <= 1;
}

// Share of background pixels in [x0,x1) x [y0,y1), clipped to the image.
double backgroundShare(const Png& png, int x0, int y0, int x1, int y1) {
  x0 = std::max(x0, 0), y0 = std::max(y0, 0), x1 = std::min(x1, png.width), y1 = std::min(y1, png.height);
  int n = 0, bg = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++n) bg += isBackground(png, x, y);
  return n > 0 ? static_cast<double>(bg) / n : -1.0;
}

class ViewerAspect : public testing::TestWithParam<AspectCase> {};

TEST_P(ViewerAspect, ImageRegionHasTheCameraAspect) {
  const AspectCase& c = GetParam();
  const std::string out = kAspectTmp + "/" + c.name + ".png";
  const std::string args = "view " + std::string(PATHLAB_SOURCE_DIR) + "/assets/" + c.scene + " --headless --width " +
                           std::to_string(c.width) + " --height " + std::to_string(c.height) +
                           " --render-scale 0.25 --spp 1 --max-length 3 --threads 2 --frames 8 --force " + c.flags +
                           " --screenshot " + out;
  const pathlab::test::CommandRun r = pathlab::test::runPathlab(kAspectTmp, args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.err, m, std::regex(R"(image (\d+)x(\d+)\+(\d+)\+(\d+) at \d+ spp, rendered (\d+)x(\d+))")))
      << r.err;
  const Rect image{std::stoi(m[3]), std::stoi(m[4]), std::stoi(m[1]), std::stoi(m[2])};
  const int renderedW = std::stoi(m[5]), renderedH = std::stoi(m[6]);

  // The drawn region and the rendered image both have the camera's shape, within one pixel.
  EXPECT_LE(std::abs(image.w - c.aspect * image.h), std::max(1.f, c.aspect)) << image.w << "x" << image.h;
  EXPECT_LE(std::abs(renderedW - c.aspect * renderedH), std::max(1.f, c.aspect)) << renderedW << "x" << renderedH;
  EXPECT_GT(image.w * image.h, c.width * c.height / 10) << "the image is a fair part of the window";

  const Png png = readPng(out);
  ASSERT_EQ(png.width, c.width);
  ASSERT_EQ(png.height, c.height);
  ASSERT_LE(image.x + image.w, png.width);
  ASSERT_LE(image.y + image.h, png.height);
  // The image reaches every edge of the region (a 2-pixel strip inside each edge is image) ...
  const int x1 = image.x + image.w, y1 = image.y + image.h;
  EXPECT_LT(backgroundShare(png, image.x, image.y, image.x + 2, y1), 0.1) << "left edge";
  EXPECT_LT(backgroundShare(png, x1 - 2, image.y, x1, y1), 0.1) << "right edge";
  EXPECT_LT(backgroundShare(png, image.x, image.y, x1, image.y + 2), 0.1) << "top edge";
  EXPECT_LT(backgroundShare(png, image.x, y1 - 2, x1, y1), 0.1) << "bottom edge";
  // ... and the bars beyond it are background. Above and below the image there is never a panel
  // here (no convergence panel); left and right there are unless the UI is hidden.
  if (image.y >= 2) {
    EXPECT_GT(backgroundShare(png, image.x, image.y - 2, x1, image.y), 0.99) << "bar above";
    EXPECT_GT(backgroundShare(png, image.x, y1, x1, y1 + 2), 0.99) << "bar below";
    EXPECT_LE(std::abs(image.y - (png.height - y1)), 1) << "centred vertically";
  }
  if (!c.panels && image.x >= 2) {
    EXPECT_GT(backgroundShare(png, image.x - 2, image.y, image.x, y1), 0.99) << "bar left";
    EXPECT_GT(backgroundShare(png, x1, image.y, x1 + 2, y1), 0.99) << "bar right";
    EXPECT_LE(std::abs(image.x - (png.width - x1)), 1) << "centred horizontally";
  }
  if (!c.panels) {
    EXPECT_TRUE(image.w == c.width || image.h == c.height) << "the image fills the window one way";
  }
}

const std::string kAspectBox = "cornell-box.gltf", kVeach = "veach-mis.gltf";

// Resizing keeps the framing: after a landscape and a portrait resize the picture is the one a
// window opened at the final size shows (seeded samples: the same pixels).
TEST(ViewerAspectResize, ResizingKeepsTheFraming) {
  const std::string common = "view " + std::string(PATHLAB_SOURCE_DIR) + "/assets/" + kVeach +
                             " --headless --hide-ui --render-scale 0.25 --spp 1 --max-length 3 --threads 2 --frames 12 --force ";
  const std::string direct = kAspectTmp + "/resize-direct.png", resized = kAspectTmp + "/resize-resized.png";
  pathlab::test::CommandRun r = pathlab::test::runPathlab(kAspectTmp, common + "--width 500 --height 900 --screenshot " + direct);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const std::string directLine = r.err;
  r = pathlab::test::runPathlab(kAspectTmp, common + "--width 640 --height 480 --script '1:resize=900,500;3:resize=500,900' --screenshot " + resized);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  // 500 / 1.5 = 333.3: 500 x 333, centred in 900.
  EXPECT_NE(r.err.find("image 500x333+0+283 "), std::string::npos) << r.err;
  EXPECT_NE(directLine.find("image 500x333+0+283 "), std::string::npos) << directLine;
  const Png a = readPng(direct), b = readPng(resized);
  ASSERT_EQ(b.width, 500);
  ASSERT_EQ(b.height, 900);
  EXPECT_LT(a.meanDifference(b, 0, 0, 500, 900), 1.0);
}

// The mouse maps to the fitted rectangle: at 800 x 1000 with the UI hidden the Cornell box is
// 800 x 800 from y = 100, so a drag in the bar above it is nobody's, and one over it orbits.
TEST(ViewerAspectInput, DragOnTheBarIsNotTheImages) {
  const std::string common = "view " + std::string(PATHLAB_SOURCE_DIR) + "/assets/" + kAspectBox +
                             " --headless --width 800 --height 1000 --hide-ui --render-scale 0.25 --spp 1 --max-length 3"
                             " --threads 2 --frames 10 --force ";
  const std::string still = kAspectTmp + "/bar-still.png", bar = kAspectTmp + "/bar-drag.png", image = kAspectTmp + "/image-drag.png";
  ASSERT_EQ(pathlab::test::runPathlab(kAspectTmp, common + "--screenshot " + still).exitCode, 0);
  pathlab::test::CommandRun r = pathlab::test::runPathlab(kAspectTmp, common + "--script '1:drag=400,40>480,70' --screenshot " + bar);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = pathlab::test::runPathlab(kAspectTmp, common + "--script '1:drag=400,500>480,530' --screenshot " + image);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png a = readPng(still), b = readPng(bar), c = readPng(image);
  ASSERT_EQ(a.width, 800);
  EXPECT_LT(a.meanDifference(b, 0, 100, 800, 900), 1.0) << "a drag on the bar moved the camera";
  EXPECT_GT(a.meanDifference(c, 0, 100, 800, 900), 5.0) << "a drag over the image did not orbit";
}

INSTANTIATE_TEST_SUITE_P(
    WindowsAndPanels, ViewerAspect,
    testing::Values(AspectCase{"box_1280x720_lecture", kAspectBox, 1.f, 1280, 720, "--lecture", true},
                    AspectCase{"veach_1280x720_lecture", kVeach, 1.5f, 1280, 720, "--lecture", true},
                    AspectCase{"box_1920x1080_pyramid", kAspectBox, 1.f, 1920, 1080, "--pyramid 3", true},
                    AspectCase{"veach_1920x1080_pyramid", kVeach, 1.5f, 1920, 1080, "--pyramid 3", true},
                    AspectCase{"box_800x1000_hidden", kAspectBox, 1.f, 800, 1000, "--hide-ui", false},
                    AspectCase{"veach_800x1000_hidden", kVeach, 1.5f, 800, 1000, "--hide-ui", false},
                    AspectCase{"veach_1280x720_hidden", kVeach, 1.5f, 1280, 720, "--hide-ui", false},
                    AspectCase{"veach_800x1000_panels", kVeach, 1.5f, 800, 1000, "", true}),
    [](const testing::TestParamInfo<AspectCase>& info) { return info.param.name; });

}  // namespace
