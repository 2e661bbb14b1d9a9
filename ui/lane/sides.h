// The two sides of the shown image: A always, B while the A | B comparison is on. They start
// together (an equal-time comparison), each on its share of the threads, and are given settings,
// pause, target, scenes and references the same way, side by side.
#pragma once

#include "ui/estimator/estimator_state.h"
#include "ui/lane/render_lane.h"

#include <memory>

namespace pathlab::ui {

class Sides {
 public:
  // What a new renderer starts with besides its settings, threads and error tracker.
  struct Start {
    uint64_t targetSpp = 0;
    int thumbnailSide = 128;
  };

  // `threads`: the render threads asked for (0: all); `errors`: the tracker both sides' passes feed.
  Sides(int threads, std::shared_ptr<ErrorTracker> errors) : threads_(threads), errors_(std::move(errors)) {}

  RenderLane& a() { return lanes_[0]; }
  RenderLane& b() { return lanes_[1]; }
  const RenderLane& a() const { return lanes_[0]; }
  const RenderLane& b() const { return lanes_[1]; }

  // Starts side A's renderer, on its share of the threads (half while `comparing`).
  void startA(const std::shared_ptr<const Scene>& scene, const RenderSettings& settings, bool comparing,
              const Start& how) {
    start(a(), scene, settings, comparing, how);
  }
  // Starts or ends side B when `on` differs from it running: the old renderers go first (joining
  // their workers), then A restarts, and B with estimator `b` in A's view; each on half of the
  // threads, A on all of them again when B ends. True when they restarted.
  bool setComparing(bool on, const std::shared_ptr<const Scene>& scene, const EstimatorState& b, const Start& how);
  // The renderers change sides with their images (RenderLane's swapRenderers).
  void swap() { swapRenderers(a(), b(), errors_); }
  // Each running side its settings: true when one took them (a new generation).
  bool apply(const RenderSettings& settingsA, const RenderSettings& settingsB);
  // Pause (the user's, or a side's idling), the sample target; per-technique timing and the
  // outlier finder's count on A only.
  void sync(bool userPaused, uint64_t targetSpp, bool timingA, int outliersA = 0);
  // The newest snapshots due (B first); true when one arrived.
  bool poll(bool force);
  // The error view's reference in both sides' image views.
  void setReference(const Image* reference);
  // Another scene on each running side.
  void setScene(const std::shared_ptr<const Scene>& scene, const RenderSettings& settingsA,
                const RenderSettings& settingsB);

 private:
  RenderLane lanes_[2] = {RenderLane(0), RenderLane(1)};
  int threads_;
  std::shared_ptr<ErrorTracker> errors_;

  void start(RenderLane& lane, const std::shared_ptr<const Scene>& scene, const RenderSettings& settings,
             bool comparing, const Start& how);
};

}  // namespace pathlab::ui
