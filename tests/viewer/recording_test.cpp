// Recording's rules alone: the frame clock (how many clip frames a drawn frame stands for), the
// frame names, the record directory's policy and ffmpeg's command line.
#include "ui/record/recording.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace {

using pathlab::ui::CaptureClock;

// N frames drawn 1/60 s apart: floor((N - 1) * fps / 60) + 1 clip frames.
int clipFrames(int drawn, int fps) {
  CaptureClock clock(fps);
  int written = 0;
  for (int i = 0; i < drawn; ++i) written += clock.framesDue(i * (1.0 / 60.0));
  return written;
}

TEST(Recording, HeadlessClockWritesADeterministicNumberOfFrames) {
  EXPECT_EQ(clipFrames(40, 30), 20);
  EXPECT_EQ(clipFrames(40, 60), 40);
  EXPECT_EQ(clipFrames(40, 120), 79);  // faster than the UI: frames repeated, real time kept
  EXPECT_EQ(clipFrames(40, 1), 1);
  EXPECT_EQ(clipFrames(61, 1), 2);
  EXPECT_EQ(clipFrames(1, 30), 1);  // the first drawn frame is always in the clip
}

// The documented rule holds exactly for every rate: the clock's times are sums of 1/60 that fall
// a rounding error short of k / fps (e.g. frame 124 at 15 fps), which must not lose a frame.
TEST(Recording, TheHeadlessRuleHoldsForEveryFrameRate) {
  for (int fps = 1; fps <= 120; ++fps) {
    CaptureClock clock(fps);
    long long written = 0;
    for (int i = 0; i < 600; ++i) {
      written += clock.framesDue(i * (1.0 / 60.0));
      ASSERT_EQ(written, static_cast<long long>(i) * fps / 60 + 1) << i + 1 << " frames at " << fps << " fps";
    }
  }
}

TEST(Recording, SlowFramesAreRepeatedAndANewTakeStartsAtZero) {
  CaptureClock clock(30);
  EXPECT_EQ(clock.framesDue(0.0), 1);
  EXPECT_EQ(clock.framesDue(0.01), 0);
  EXPECT_EQ(clock.framesDue(0.5), 15);  // frames 1..15 (t = 1/30 .. 15/30) all stand on this one
  clock.restart();
  EXPECT_EQ(clock.framesDue(0.0), 1);
}

TEST(Recording, FrameNamesMatchFfmpegsPattern) {
  EXPECT_EQ(pathlab::ui::recordFrameName("clips", 42), "clips/frame-00042.png");
  const std::vector<std::string> expected = {"ffmpeg", "-y", "-framerate", "24", "-i", "clips/frame-%05d.png",
                                             "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", "-pix_fmt", "yuv420p",
                                             "clips/recording.mp4"};
  EXPECT_EQ(pathlab::ui::ffmpegArguments("clips", 24), expected);
}

TEST(Recording, ADirectoryWithFilesIsKeptUnlessForced) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(PATHLAB_TEST_TMP) / "recording_unit" / "dir";
  fs::remove_all(dir.parent_path());
  fs::create_directories(dir.parent_path());
  pathlab::ui::prepareRecordDirectory(dir.string(), false);  // created
  EXPECT_TRUE(fs::is_directory(dir));
  pathlab::ui::prepareRecordDirectory(dir.string(), false);  // empty: fine
  std::ofstream(dir / "notes.txt") << "mine";
  std::ofstream(dir / "frame-00003.png") << "old";
  std::ofstream(dir / "recording.mp4") << "old";
  EXPECT_THROW(pathlab::ui::prepareRecordDirectory(dir.string(), false), std::runtime_error);
  EXPECT_TRUE(fs::exists(dir / "frame-00003.png"));
  pathlab::ui::prepareRecordDirectory(dir.string(), true);  // only a recording's own files go
  EXPECT_TRUE(fs::exists(dir / "notes.txt"));
  EXPECT_FALSE(fs::exists(dir / "frame-00003.png"));
  EXPECT_FALSE(fs::exists(dir / "recording.mp4"));
  EXPECT_THROW(pathlab::ui::prepareRecordDirectory((dir / "missing" / "deeper").string(), false), std::runtime_error);
}

}  // namespace
