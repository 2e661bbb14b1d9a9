// Takes started and stopped, frames captured on the take's clock, the recorder's reports shown.
#include "ui/record/recording_controller.h"

#include "ui/gl/screenshot.h"
#include "ui/record/output_names.h"
#include "ui/record/recording.h"

#include <fmt/core.h>

#include <iostream>

namespace pathlab::ui {

void RecordingController::start(Viewer& viewer, const std::string& dir) {
  if (!recorder_) recorder_ = std::make_unique<Recorder>(dir, fps_, headless_);
  recorder_->start();
  takeFrames_ = 0;
  takeStart_ = std::chrono::steady_clock::now();
  viewer.setRecording(true);
  std::cerr << fmt::format("pathlab view: recording into {} at {} fps\n", recorder_->dir(), fps_);
}

void RecordingController::toggle(Viewer& viewer) {
  if (active()) {
    recorder_->stop();
    viewer.setRecording(false);
    return;
  }
  try {
    std::string dir = recorder_ ? recorder_->dir() : freshStem("out", "pathlab-recording", {""});
    if (!recorder_) prepareRecordDirectory(dir, false);
    start(viewer, dir);
  } catch (const std::exception& e) {
    viewer.showMessage(e.what(), true);
  }
}

void RecordingController::capture(const Viewer& viewer, Vec2i fb) {
  if (!active()) return;
  const double t = headless_ ? static_cast<double>(takeFrames_) * frameSeconds_
                             : std::chrono::duration<double>(std::chrono::steady_clock::now() - takeStart_).count();
  ++takeFrames_;
  const int copies = recorder_->framesDue(t);
  if (copies == 0) return;
  // The image area includes the caption drawn over it (ImGui's foreground list is drawn by now).
  const Vec2i origin = imageOnly_ ? viewer.imageOrigin() : Vec2i(0);
  const Vec2i size = imageOnly_ ? viewer.imageSize() : fb;
  if (size.x <= 0 || size.y <= 0) return;
  recorder_->submit(readFramebufferRgba(fb, origin, size), size, copies);
}

void RecordingController::report(Viewer* viewer) {
  if (!recorder_) return;
  while (const std::optional<std::string> r = recorder_->takeReport()) {
    std::cerr << "pathlab view: " << *r << "\n";
    if (viewer) viewer->showMessage(*r, r->starts_with("warning"));
  }
}

void RecordingController::finish() {
  if (!recorder_) return;
  recorder_->finish();
  report(nullptr);
}

}  // namespace pathlab::ui
