// Progressive multithreaded rendering: one pass = one camera sample per pixel, tiles in parallel.
// Sample `pass` of pixel (x, y) draws from the stream keyed by (seed, pixel, pass), so any sample
// can be replayed alone.
#pragma once

#include "core/bpt/bidir_tracer.h"
#include "core/film/film.h"
#include "core/metrics/counters.h"
#include "core/pt/path_tracer.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

#include <atomic>
#include <memory>

namespace pathlab {

class RenderSession {
 public:
  RenderSession(const Scene& scene, const RenderSettings& settings);

  // Renders one more pass over the whole film (blocking; uses the TBB arena of the caller).
  void renderPass();
  // The estimate of one camera sample, exactly as renderPass computes it (for replay and tests).
  // For Bpt and Lt this is the camera-side part only: the t = 1 splats of the sample's light
  // subpath go to the film during renderPass, never here.
  Spectrum replaySample(int x, int y, uint64_t pass, Counters& counters) const;

  const Film& film() const { return film_; }
  Image image() const { return film_.readout(); }
  const Counters& counters() const { return counters_; }
  uint64_t passes() const { return passes_; }
  const RenderSettings& settings() const { return settings_; }
  const Camera& camera() const { return camera_; }
  // Pixels finished in the current pass, for progress reporting from another thread.
  uint64_t pixelsDoneInPass() const { return pixelsDone_.load(std::memory_order_relaxed); }

 private:
  const Scene& scene_;
  RenderSettings settings_;
  Camera camera_;
  PathTracer pathTracer_;
  std::unique_ptr<BidirTracer> bidirTracer_;  // Bpt and Lt

  Spectrum sampleAt(int x, int y, uint64_t pass, Film* film, Counters& counters) const;
  Film film_;
  Counters counters_;
  uint64_t passes_ = 0;
  std::atomic<uint64_t> pixelsDone_{0};
};

}  // namespace pathlab
