// `pathlab view --headless --record DIR`: the simulated clock writes a known number of frames of
// the window's (or the image's) size; F9 records only between its presses; transient notices stay
// out of the clip; bad input is one line and a non-zero exit; ffmpeg is optional and its failure a
// warning. Headless, every drawn frame advances the clip clock by the UI period of 1/60 s, so N
// drawn frames at F fps give floor((N - 1) * F / 60) + 1 frames (40 at 30 fps: 20).
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using pathlab::test::Png;
using pathlab::test::readPng;
using pathlab::test::CommandRun;

const std::string kRecordTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_record";
const std::string kRecordBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";
const std::string kRecordFast = " --headless --width 400 --height 300 --render-scale 0.25 --threads 2 --max-length 3 ";
// No ffmpeg on the path (whatever the machine has): the clip is frames only.
const std::string kNoFfmpeg = "PATH=/nonexistent";

CommandRun runRecordingView(const std::string& args, const std::string& prefix = kNoFfmpeg) {
  return pathlab::test::runPathlab(kRecordTmp, "view " + kRecordBox + args, prefix);
}

// `pathlab view` started in a fresh working directory `work` (for what it writes to out/).
CommandRun runViewIn(const std::string& work, const std::string& args) {
  fs::remove_all(work);
  fs::create_directories(work);
  return runRecordingView(args, "cd " + work + " && " + kNoFfmpeg);
}

// A fresh, absent directory for one test.
std::string freshDir(const std::string& name) {
  const std::string dir = kRecordTmp + "/" + name;
  fs::remove_all(dir);
  fs::create_directories(kRecordTmp);
  return dir;
}

std::vector<std::string> framesIn(const std::string& dir) {
  std::vector<std::string> names;
  if (!fs::is_directory(dir)) return names;
  for (const fs::directory_entry& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".png") names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// frame-00000.png .. frame-(n-1).png, nothing else.
void expectNumberedFrames(const std::string& dir, int n) {
  const std::vector<std::string> names = framesIn(dir);
  ASSERT_EQ(static_cast<int>(names.size()), n) << dir;
  for (int k = 0; k < n; ++k) {
    char expected[32];
    std::snprintf(expected, sizeof expected, "frame-%05d.png", k);
    EXPECT_EQ(names[static_cast<size_t>(k)], expected);
  }
}

TEST(ViewerRecord, HeadlessClockWritesTheExpectedFramesOfTheWindowSize) {
  const std::string dir = freshDir("window");
  const CommandRun r = runRecordingView(kRecordFast + "--frames 40 --record-fps 30 --record " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectNumberedFrames(dir, 20);
  for (const std::string& name : framesIn(dir)) {
    const Png png = readPng(dir + "/" + name);
    EXPECT_EQ(png.width, 400) << name;
    EXPECT_EQ(png.height, 300) << name;
  }
  EXPECT_GT(readPng(dir + "/frame-00019.png").variance(270, 20, 400, 270), 10.0);  // the box is there
  // Without ffmpeg: a note, no warning or error.
  EXPECT_NE(r.err.find("20 frames at 30 fps; ffmpeg not found"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/recording.mp4"));
}

TEST(ViewerRecord, ImageOnlyFramesHaveTheImageAreaSizeWithItsCaption) {
  const std::string dir = freshDir("image");
  const CommandRun r = runRecordingView(kRecordFast + "--frames 10 --record-fps 60 --record-image --record " + dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectNumberedFrames(dir, 10);
  // The side panel takes 0.45 of a 400-pixel window, leaving 220 x 300, and the Cornell box's
  // square image is letterboxed in it: the image area is 220 x 220.
  const Png png = readPng(dir + "/frame-00009.png");
  EXPECT_EQ(png.width, 220);
  EXPECT_EQ(png.height, 220);
  // The caption, wrapped to the narrow image, along its bottom: near-white text on a dark box,
  // where the floor behind it has no pixel that bright.
  auto brightPixels = [&](int x0, int y0, int x1, int y1) {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        n += (png.rgb[png.index(x, y, 0)] > 215 && png.rgb[png.index(x, y, 1)] > 215 && png.rgb[png.index(x, y, 2)] > 215) ? 1 : 0;
    return n;
  };
  EXPECT_GT(brightPixels(0, 170, 220, 220), 40);
}

// Without --record, F9 starts a take in a fresh out/pathlab-recording-* and F9 stops it: frames
// 10..29 are recorded (20 drawn frames, 10 clip frames at 30 fps), nothing before or after.
TEST(ViewerRecord, TheKeyRecordsOnlyBetweenItsPresses) {
  const std::string work = kRecordTmp + "/key";
  const CommandRun r = runViewIn(work, kRecordFast + "--frames 40 --screenshot shot.png --script '10:key=F9;30:key=F9'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  std::vector<fs::path> takes;
  for (const fs::directory_entry& e : fs::directory_iterator(work + "/out")) takes.push_back(e.path());
  ASSERT_EQ(takes.size(), 1u);
  EXPECT_EQ(takes[0].filename().string().rfind("pathlab-recording-", 0), 0u) << takes[0];
  expectNumberedFrames(takes[0].string(), 10);
}

// With --record, F9 pauses and resumes the recording in the same directory: frames 0..9 and
// 30..39 (5 + 5 clip frames), numbered without a gap.
TEST(ViewerRecord, TheKeyPausesAndResumesARecordingFromTheCommandLine) {
  const std::string dir = freshDir("pause");
  const CommandRun r = runRecordingView(kRecordFast + "--frames 40 --record " + dir + " --script '10:key=F9;30:key=F9'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectNumberedFrames(dir, 10);
}

// F12 during a recording: the screenshot is written, but its "screenshot ..." notice (green, at
// the top of the panel) is not in the recorded frames: the panel's top looks as before the press.
TEST(ViewerRecord, TransientNoticesStayOutOfTheClip) {
  const std::string work = kRecordTmp + "/notice";
  const CommandRun r = runViewIn(work, kRecordFast + "--frames 20 --record-fps 60 --record clip --script '8:key=F12'");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  ASSERT_EQ(framesIn(work + "/out").size(), 1u);  // the screenshot was taken
  const Png before = readPng(work + "/clip/frame-00007.png"), after = readPng(work + "/clip/frame-00012.png");
  ASSERT_EQ(before.width, 400);
  ASSERT_EQ(after.width, 400);
  EXPECT_LT(before.meanDifference(after, 0, 0, 175, 60), 0.5);  // the panel is 180 wide
}

// A fake ffmpeg on the path: its argument vector is the documented one, and its failure is one
// warning line with the frames kept.
TEST(ViewerRecord, FfmpegIsCalledWithoutAShellAndItsFailureIsOneWarning) {
  const std::string dir = freshDir("ffmpeg"), bin = freshDir("fake-bin");
  fs::create_directories(bin);
  const std::string args = bin + "/args.txt";
  std::ofstream(bin + "/ffmpeg") << "#!/bin/sh\nfor a in \"$@\"; do echo \"$a\"; done > " << args
                                 << "\necho 'frame size mismatch' >&2\nexit 3\n";
  fs::permissions(bin + "/ffmpeg", fs::perms::owner_all);
  const CommandRun r = runRecordingView(kRecordFast + "--frames 4 --record-fps 60 --record " + dir, "PATH=" + bin + ":/usr/bin:/bin");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectNumberedFrames(dir, 4);
  std::ifstream in(args);
  std::vector<std::string> got;
  for (std::string line; std::getline(in, line);) got.push_back(line);
  const std::vector<std::string> expected = {"-y", "-framerate", "60", "-i", dir + "/frame-%05d.png", "-vf",
                                             "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p",
                                             dir + "/recording.mp4"};
  EXPECT_EQ(got, expected);
  const size_t warnings = r.err.find("warning: ");
  ASSERT_NE(warnings, std::string::npos) << r.err;
  const std::string line = r.err.substr(warnings, r.err.find('\n', warnings) - warnings);
  EXPECT_NE(line.find("ffmpeg failed (exit 3: frame size mismatch), frames kept"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("warning:", warnings + 1), std::string::npos) << r.err;
}

TEST(ViewerRecord, BadInputIsOneLineAndNothingIsOverwritten) {
  const std::string full = freshDir("full");
  fs::create_directories(full);
  std::ofstream(full + "/lecture-notes.txt") << "precious";
  const std::string ok = freshDir("unused");
  for (const std::string& args :
       {kRecordFast + "--frames 2 --record " + full, kRecordFast + "--frames 2 --record-fps 0 --record " + ok,
        kRecordFast + "--frames 2 --record-fps 121 --record " + ok,
        kRecordFast + "--frames 2 --record-image --screenshot " + kRecordTmp + "/x.png --force",
        kRecordFast + "--frames 2 --record /nonexistent/deeper/clip", kRecordFast + "--frames 2 --record " + full + "/lecture-notes.txt"}) {
    const CommandRun r = runRecordingView(args);
    EXPECT_NE(r.exitCode, 0) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
  EXPECT_TRUE(framesIn(full).empty());
  std::ifstream in(full + "/lecture-notes.txt");
  std::string content;
  in >> content;
  EXPECT_EQ(content, "precious");
  EXPECT_FALSE(fs::exists(ok));
}

}  // namespace
