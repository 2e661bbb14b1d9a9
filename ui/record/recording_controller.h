// Recording in the viewer (R, or --record DIR): the recorder and its take's clock, started and
// stopped by request, fed the frames drawn, its reports sent to the message line and stderr.
// Headless, every drawn frame advances the clock by the UI frame period (a simulated clock: the
// same script writes the same frames on any machine); in a window it is the wall clock, so the
// clip plays at the speed the lecture happened.
#pragma once

#include "ui/record/recorder.h"
#include "ui/viewer.h"

#include <chrono>
#include <memory>
#include <string>

namespace pathlab::ui {

class RecordingController {
 public:
  // `frameSeconds`: the UI frame period (the headless clock's step); `imageOnly`: record the
  // image area only (--record-image), else the whole window.
  RecordingController(bool headless, bool imageOnly, int fps, double frameSeconds)
      : headless_(headless), imageOnly_(imageOnly), fps_(fps), frameSeconds_(frameSeconds) {}

  bool active() const { return recorder_ && recorder_->recording(); }
  // A take into `dir` (prepared already).
  void start(Viewer& viewer, const std::string& dir);
  // Stops the take, or starts one (without --record, in a fresh directory beside the screenshots).
  void toggle(Viewer& viewer);
  // After the frame is drawn, before it is presented: the frames due at this point of the take.
  void capture(const Viewer& viewer, Vec2i framebufferSize);
  // The recorder's reports to stderr and (`viewer` not null) the message line.
  void report(Viewer* viewer);
  // The last frames written and the clip assembled.
  void finish();

 private:
  std::unique_ptr<Recorder> recorder_;
  bool headless_, imageOnly_;
  int fps_;
  double frameSeconds_;
  long long takeFrames_ = 0;  // frames drawn in this take
  std::chrono::steady_clock::time_point takeStart_{};
};

}  // namespace pathlab::ui
