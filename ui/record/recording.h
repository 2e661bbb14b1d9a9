// Recording's rules without OpenGL or threads (so they are unit-tested alone): when a frame is
// captured, how frames are named, what the record directory may hold, how ffmpeg is called.
#pragma once

#include <string>
#include <vector>

namespace pathlab::ui {

// The clip has a fixed frame rate: frame k stands for clip time k / fps. A drawn UI frame at clock
// time t (seconds since the take started) is written once for every frame time k / fps <= t not
// yet written, so the clip keeps real time when the UI is slower than the clip (a frame is then
// repeated) and skips UI frames when it is faster. Headless, t is the drawn frame's index times the
// UI frame period, which makes the count deterministic: N drawn frames give
// floor((N - 1) * fps * period) + 1 clip frames (40 frames at 1/60 s and 30 fps: 20).
class CaptureClock {
 public:
  explicit CaptureClock(int fps) : fps_(fps) {}
  // How many clip frames the UI frame at clock time `seconds` stands for (0: none is due).
  int framesDue(double seconds);
  // A new take: its clock starts again at zero (clip frames go on from where they were).
  void restart() { taken_ = 0; }

 private:
  int fps_;
  long long taken_ = 0;  // clip frames of this take written so far
};

// "DIR/frame-00042.png": the names ffmpeg's "frame-%05d.png" pattern reads.
std::string recordFrameName(const std::string& dir, long long index);

// The record directory before the first frame: created when missing (its parent must exist);
// refused when it holds anything, unless `force`, which removes only what a recording writes there
// (frame-NNNNN.png, recording.mp4), so no old frame ends up in the new clip. Throws
// std::runtime_error "DIR: PROBLEM".
void prepareRecordDirectory(const std::string& dir, bool force);

// ffmpeg's argument vector (argv[0] = "ffmpeg") to assemble DIR/recording.mp4 from the frames.
// The pad filter rounds the size up to even numbers, which yuv420p needs (an image-only capture
// can be odd).
std::vector<std::string> ffmpegArguments(const std::string& dir, int fps);

// The full path of an executable `name` in $PATH, or "" when there is none.
std::string findInPath(const std::string& name);

}  // namespace pathlab::ui
