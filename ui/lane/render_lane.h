// One side of the shown image, A or B of the A | B comparison alike: a progressive renderer, the
// settings last handed to it, the image view it is shown in, its newest snapshot, when that was
// polled, and the error series its passes feed. The Viewer holds two; only A shows the pyramid,
// the maps and the check (the settings it is given say so).
#pragma once

#include "core/converge/error_tracker.h"
#include "core/render/progressive_renderer.h"
#include "ui/display/display_settings.h"
#include "ui/display/image_rect.h"
#include "ui/gl/image_view.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

namespace pathlab::ui {

// What a lane's renderer starts with besides its settings.
struct LaneStart {
  int threads = 0;  // 0: all hardware threads
  uint64_t targetSpp = 0;
  int thumbnailSide = 128;
  std::shared_ptr<ErrorTracker> errors;  // measures each full pass into the lane's series
};

class RenderLane {
 public:
  // `series`: the lane's index in the error tracker (ErrorTracker::observe): 0 for A, 1 for B.
  explicit RenderLane(int series) : series_(series) {}

  bool running() const { return renderer_ != nullptr; }
  ProgressiveRenderer& renderer() { return *renderer_; }
  const RenderSettings& applied() const { return applied_; }
  // Why the renderer refused the last settings or scene ("" when it took them).
  const std::string& refused() const { return refused_; }
  // No technique enabled: the renderer idles and the image is black.
  bool idle() const { return idle_; }
  const RenderSnapshot& snapshot() const { return snapshot_; }
  ImageView& view() { return *view_; }

  // Where the image goes this frame and where the last draw put it, framebuffer pixels.
  PixelRect rect;
  PixelRect drawn() const { return drawn_; }

  // A new renderer of `settings` (the old one goes first); its applied state and snapshot start
  // afresh, the image view is kept (made on the first start).
  void start(const std::shared_ptr<const Scene>& scene, const RenderSettings& settings, const LaneStart& how);
  // Ends the renderer, joining its workers (the view and the snapshot stay).
  void stop() { renderer_.reset(); }
  // Hands the renderer `wanted` unless it enables no technique (the lane idles) or is what it has:
  // true when the renderer took them (a new generation), else refused() says why not.
  bool apply(const RenderSettings& wanted);
  // Another scene with `settings`; refused() says why it was not taken.
  void setScene(const std::shared_ptr<const Scene>& scene, const RenderSettings& settings);
  // Pause (the user's, or idle), the sample target, per-technique timing and the outlier finder's
  // count (ProgressiveRenderer::setOutlierCount, 0: off), as they change.
  void sync(bool userPaused, uint64_t targetSpp, bool timing, int outliers = 0);
  // Takes the newest snapshot into the view when one is due (or `force`): true when one was.
  bool poll(bool force);
  // Draws the image into `rect` (nothing while idle); drawn() says where it went.
  void draw(int framebufferHeight, const DisplaySettings& display);
  // The sides exchange their renderers with everything that follows them (settings, snapshot,
  // view); each keeps its rect and its error series, which its new renderer now feeds.
  friend void swapRenderers(RenderLane& a, RenderLane& b, const std::shared_ptr<ErrorTracker>& errors);

 private:
  int series_;
  std::unique_ptr<ProgressiveRenderer> renderer_;
  RenderSettings applied_;  // last handed to the renderer (or refused by it)
  std::string refused_;
  bool idle_ = false;
  bool pausedApplied_ = false, timingApplied_ = false;
  int outliersApplied_ = 0;
  uint64_t targetApplied_ = 0;
  std::unique_ptr<ImageView> view_;
  RenderSnapshot snapshot_;
  std::chrono::steady_clock::time_point lastPoll_{};
  PixelRect drawn_;

  void observe(const std::shared_ptr<ErrorTracker>& errors);
};

}  // namespace pathlab::ui
