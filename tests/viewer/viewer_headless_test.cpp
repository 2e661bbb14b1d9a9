// The whole viewer, panels included, drawn offscreen through EGL by `pathlab view --headless`:
// the screenshot has the window's size and shows an image; a technique preset changes the image
// and nothing else; existing files are kept; bad input is one line and a non-zero exit.
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sys/wait.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_headless";

using pathlab::test::Png;
using pathlab::test::readPng;
using ViewRun = pathlab::test::CommandRun;

ViewRun runView(const std::string& args) { return pathlab::test::runPathlab(kTmp, "view " + args); }

const std::string kBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";
// Small and short, so a run takes about a second: 2 samples per pixel at a quarter resolution.
const std::string kFast = " --width 400 --height 300 --render-scale 0.25 --spp 2 --threads 2 --force ";
// The panel is at most 0.6 of the width: the right third is image.
constexpr int kImageX0 = 270, kImageX1 = 400, kImageY0 = 20, kImageY1 = 270;

TEST(ViewerHeadless, ScreenshotHasTheWindowSizeAndShowsPanelsAndImage) {
  const std::string out = kTmp + "/all.png";
  const ViewRun r = runView(kBox + kFast + "--frames 6 --headless --max-length 4 --screenshot " + out);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png png = readPng(out);
  ASSERT_EQ(png.width, 400);
  ASSERT_EQ(png.height, 300);
  // Not uniform: the panel has text, the image has the box.
  EXPECT_GT(png.variance(0, 0, 200, 300), 10.0);
  EXPECT_GT(png.variance(kImageX0, kImageY0, kImageX1, kImageY1), 10.0);
  // The frame-time summary is printed for the report.
  EXPECT_NE(r.err.find("UI frame time mean"), std::string::npos) << r.err;
}

TEST(ViewerHeadless, TechniquePresetsChangeTheImageNotThePanelLayout) {
  const std::string presets = kTmp + "/presets.json";
  // The file first, in a directory that may not exist yet: under ctest -j2 this test can be the
  // first of the file to run (runView makes the directory only when it runs).
  std::filesystem::create_directories(kTmp);
  std::ofstream(presets) << R"({"presets": [{"name": "all", "maxLength": 4},
                                            {"name": "emitters only", "techniques": "0,2", "maxLength": 4}]})";
  const std::string a = kTmp + "/preset-all.png", b = kTmp + "/preset-emitters.png";
  const ViewRun all = runView(kBox + kFast + "--frames 6 --headless --hide-ui --presets " + presets + " --preset all --screenshot " + a);
  ASSERT_EQ(all.exitCode, 0) << all.err;
  const ViewRun r = runView(kBox + kFast + "--frames 6 --headless --hide-ui --presets " + presets + " --preset 'emitters only' --screenshot " + b);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png pa = readPng(a), pb = readPng(b);
  ASSERT_EQ(pa.width, pb.width);
  // Only (0,2), the emitter seen directly: the walls go black, the image changes a lot.
  EXPECT_GT(pa.meanDifference(pb, 60, 20, 340, 260), 10.0);
  // ... and the same preset twice gives the same picture (seeded samples).
  const std::string c = kTmp + "/preset-all-again.png";
  ASSERT_EQ(runView(kBox + kFast + "--frames 6 --headless --hide-ui --presets " + presets + " --preset all --screenshot " + c).exitCode, 0);
  EXPECT_LT(pa.meanDifference(readPng(c), 60, 20, 340, 260), 1.0);
}

// Scripted input goes through the same ImGui path as a user's: a key press switches the techniques
// exactly as the command line does; a drag over the image orbits; R resets the camera.
TEST(ViewerHeadless, ShortcutKeysActLikeTheCommandLine) {
  const std::string fast = kFast + "--frames 8 --headless --hide-ui --max-length 4 ";
  const std::string byKey = kTmp + "/key-lt.png", byOption = kTmp + "/option-lt.png", all = kTmp + "/key-none.png";
  ViewRun r = runView(kBox + fast + "--script '1:key=3' --screenshot " + byKey);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runView(kBox + fast + "--techniques t=1 --screenshot " + byOption);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runView(kBox + fast + "--screenshot " + all);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png key = readPng(byKey), option = readPng(byOption), none = readPng(all);
  EXPECT_LT(key.meanDifference(option, 0, 0, 400, 300), 1.0);
  EXPECT_GT(key.meanDifference(none, 60, 20, 340, 260), 2.0);
}

TEST(ViewerHeadless, DragOrbitsAndResetReturns) {
  const std::string fast = kFast + "--frames 10 --headless --hide-ui --max-length 3 ";
  const std::string still = kTmp + "/still.png", dragged = kTmp + "/dragged.png", reset = kTmp + "/reset.png";
  ASSERT_EQ(runView(kBox + fast + "--screenshot " + still).exitCode, 0);
  ViewRun r = runView(kBox + fast + "--script '1:drag=200,150>260,170' --screenshot " + dragged);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runView(kBox + fast + "--script '1:drag=200,150>260,170;6:key=R' --screenshot " + reset);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png a = readPng(still), b = readPng(dragged), c = readPng(reset);
  EXPECT_GT(a.meanDifference(b, 60, 20, 340, 260), 5.0);
  EXPECT_LT(a.meanDifference(c, 0, 0, 400, 300), 1.0);
}

// A dropped file goes through the scene loader: a broken one is reported in the UI and the
// previous scene stays; a good one replaces it.
TEST(ViewerHeadless, DroppedScenesLoadOrKeepThePreviousOne) {
  const std::string fast = kFast + "--frames 12 --headless --max-length 3 ";
  const std::string bad = std::string(PATHLAB_SOURCE_DIR) + "/tests/scenes/bad/not-json.gltf";
  const std::string lamp = std::string(PATHLAB_SOURCE_DIR) + "/assets/bidir-lamp.gltf";
  const std::string before = kTmp + "/drop-none.png", broken = kTmp + "/drop-broken.png", good = kTmp + "/drop-good.png";
  ASSERT_EQ(runView(kBox + fast + "--screenshot " + before).exitCode, 0);
  ViewRun r = runView(kBox + fast + "--script '1:drop=" + bad + "' --screenshot " + broken);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = runView(kBox + fast + "--script '1:drop=" + lamp + "' --screenshot " + good);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png a = readPng(before), b = readPng(broken), c = readPng(good);
  EXPECT_LT(a.meanDifference(b, kImageX0, kImageY0, kImageX1, kImageY1), 1.0);  // same scene, same image
  EXPECT_GT(a.meanDifference(b, 0, 0, 200, 100), 0.5);  // but the panel shows the error
  EXPECT_GT(a.meanDifference(c, kImageX0, kImageY0, kImageX1, kImageY1), 3.0);
}

// Resizing, also many times in a row: every size is a new generation, the last one is shown.
TEST(ViewerHeadless, ResizesFollowTheWindow) {
  const std::string out = kTmp + "/resized.png";
  const ViewRun r = runView(kBox + kFast + "--headless --frames 12 --max-length 3 --screenshot " + out +
                            " --script '1:resize=640,480;2:resize=300,200;3:resize=500,260;4:resize=64,64;5:resize=520,330'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png png = readPng(out);
  EXPECT_EQ(png.width, 520);
  EXPECT_EQ(png.height, 330);
  EXPECT_GT(png.variance(350, 20, 500, 300), 10.0);  // the image is there, at the new size
}

// Closing in the middle of a long full-resolution pass: the renderer cancels it and exits at once.
TEST(ViewerHeadless, ClosesWhileRendering) {
  const auto start = std::chrono::steady_clock::now();
  const ViewRun r = runView(kBox + " --headless --frames 3 --width 800 --height 600 --max-length 20 --force --screenshot " +
                            kTmp + "/closing.png");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
}

// Issue 14: a notice ("screenshot out/...") is not part of the picture: the second of two F12
// screenshots shows the panel as the first did, without the first one's notice.
TEST(ViewerHeadless, ScreenshotsLeaveOutTheNoticeOfTheLastOne) {
  const std::string dir = kTmp + "/notice";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string command = "cd " + dir + " && " + std::string(PATHLAB_BINARY) + " view " + kBox + kFast +
                              "--frames 12 --headless --script '4:key=F12;8:key=F12' --screenshot last.png 2>err.txt";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::vector<std::string> shots;
  for (const auto& e : std::filesystem::directory_iterator(dir + "/out")) shots.push_back(e.path().string());
  ASSERT_EQ(shots.size(), 2u);
  std::sort(shots.begin(), shots.end());  // pathlab-screenshot-TIME.png, then ...-TIME-2.png
  if (shots[0].find("-2.png") != std::string::npos) std::swap(shots[0], shots[1]);
  const Png first = readPng(shots[0]), second = readPng(shots[1]);
  // The panel's top: the title and Help button, then the Status header (or a notice pushing it
  // down, from y = 45 at this size). Only the panel (x < 170): the image starts at x = 180 and may
  // have rendered another pass between the two shots on a loaded machine.
  EXPECT_LT(first.meanDifference(second, 0, 0, 170, 70), 1.0);
}

TEST(ViewerHeadless, KeepsAnExistingScreenshotWithoutForce) {
  const std::string out = kTmp + "/existing.png";
  std::filesystem::create_directories(kTmp);  // this test may be the file's first to run
  std::ofstream(out) << "precious";
  const ViewRun r = runView(kBox + " --headless --frames 2 --screenshot " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("--force"), std::string::npos) << r.err;
  std::ifstream in(out);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");
}

TEST(ViewerHeadless, BadInputIsOneLine) {
  for (const std::string& args :
       {std::string(" /nonexistent/box.gltf --headless --frames 2 --screenshot " + kTmp + "/x.png --force"),
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.png --force --presets /nonexistent/p.json",
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.png --force --techniques '1;x'",
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.jpg --force",
        kBox + " --headless --frames 2 --force",
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.png --force --isolate 9,9 --max-length 4",
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.png --force --presets " + std::string(PATHLAB_SOURCE_DIR) +
            "/assets/presets.json --preset nope",
        kBox + " --headless --frames 2 --screenshot " + kTmp + "/x.png --force --script '1:key=nope'"}) {
    const ViewRun r = runView(args);
    EXPECT_EQ(r.exitCode, 1) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
