// The progressive renderer behind the viewer: a worker thread renders passes of a RenderSession
// while another thread (the UI) changes settings and takes snapshots.
//
// Generations: every change of settings or scene starts a new generation with a fresh film. The
// pass in flight is cancelled (checked between tiles) and its film dropped, so work of an old
// generation never reaches the new image. A generation starts with preview passes at 1/8, 1/4
// and 1/2 resolution (1 sample per pixel each, Cycles-style) so the first new image arrives
// within a few tens of milliseconds; full-resolution passes then accumulate.
#pragma once

#include "core/bpt/light_path_choice.h"
#include "core/check/check_report.h"
#include "core/film/downsample.h"
#include "core/film/film.h"
#include "core/maps/technique_maps.h"
#include "core/counters/counters.h"
#include "core/mlt/metropolis.h"
#include "core/render/outliers.h"
#include "core/render/render_settings.h"
#include "core/scene/scene.h"

#include <functional>
#include <memory>
#include <vector>

namespace pathlab {

// One displayable state of the current generation. `image` has the preview's resolution while
// `preview` is true (scale it up to width x height to show it).
struct RenderSnapshot {
  Image image;
  uint64_t generation = 0;
  uint64_t version = 0;           // increases with every published image (any generation)
  bool preview = false;
  int previewFactor = 1;          // image is (width / f) x (height / f), rounded up
  uint64_t samplesPerPixel = 0;   // full-resolution passes accumulated
  double seconds = 0.0;           // wall time of this generation so far
  double renderSeconds = 0.0;     // time spent in its passes (previews included): pauses excluded
  Counters counters;              // of this generation (full passes and previews)
  RenderSettings settings;        // the settings this image was rendered with
  // The consistency check over this generation's full passes (settings.checkTechniques), else null.
  std::shared_ptr<const CheckReport> check;
  // The Metropolis chains' normalisation and acceptance after the last full pass (Mlt), else null.
  std::shared_ptr<const MltSummary> mlt;
  // --light-paths auto: the F chosen so far and the candidates' estimates after the last full pass, else null.
  std::shared_ptr<const LightPathStatus> lightPaths;
};

// The outlier finder's list over the current generation's full passes (ProgressiveRenderer::outliers).
struct OutlierList {
  std::vector<Outlier> top;  // brightest first
  uint64_t generation = 0;
  uint64_t firstPass = 0;    // the passes it covers: firstPass .. passes - 1 (the finder starts between passes)
  uint64_t passes = 0;
  RenderSettings settings;   // what they were rendered with: a replay of one (replayOutlier) takes these
};

// What the pass observer sees after every full-resolution pass, on the render thread.
struct PassInfo {
  uint64_t generation = 0;
  const RenderSettings& settings;
  const Scene* scene = nullptr;
  uint64_t samplesPerPixel = 0;
  double renderSeconds = 0.0;  // as RenderSnapshot::renderSeconds, up to the end of this pass
};
// Called on the render thread with the generation's mean image after every full pass, before
// the image is published; its own time is not counted in renderSeconds. It must be quick (it
// delays the next pass) and must not call back into the renderer.
using PassObserver = std::function<void(const PassInfo&, const Image&)>;

class ProgressiveRenderer {
 public:
  // threads = 0: all hardware threads. The worker starts rendering at once.
  ProgressiveRenderer(std::shared_ptr<const Scene> scene, const RenderSettings& settings, int threads = 0);
  ~ProgressiveRenderer();  // cancels the pass in flight and joins the worker
  ProgressiveRenderer(const ProgressiveRenderer&) = delete;
  ProgressiveRenderer& operator=(const ProgressiveRenderer&) = delete;

  // Starts a new generation when `settings` differs from the current ones; returns whether it did.
  // Throws std::invalid_argument (and changes nothing) for settings the renderer cannot use, such
  // as a bad technique SPEC or an isolated technique longer than maxLength.
  bool setSettings(const RenderSettings& settings);
  // A new scene always starts a new generation.
  void setScene(std::shared_ptr<const Scene> scene, const RenderSettings& settings);
  RenderSettings settings() const;
  std::shared_ptr<const Scene> scene() const;
  uint64_t generation() const;

  // Paused: the pass in flight finishes, no new one starts. Accumulation resumes on unpause.
  void setPaused(bool paused);
  bool paused() const;
  // Stop after this many full-resolution samples per pixel (0: never).
  void setTargetSpp(uint64_t spp);

  // Copies the newest published image into `out` if its version is newer than out.version;
  // returns whether it did. Cheap when nothing new was published.
  bool snapshot(RenderSnapshot& out) const;
  // Thumbnails of the technique pyramid (settings.pyramidLength > 0), box-downsampled to at most
  // thumbnailSide pixels on the longer side, published after every full pass; returns false when
  // there is none or nothing newer than `version` (updated on success).
  bool pyramid(std::vector<TechniqueThumbnail>& out, uint64_t& version) const;
  void setThumbnailSide(int side);  // default 128; used from the next publication on
  // The technique maps' luminances (settings.techniqueMaps), full resolution, published after
  // every full pass like the thumbnails; the viewer colours whichever map is chosen from them, so
  // changing the map never restarts the image.
  bool techniqueMaps(TechniqueLuminance& out, uint64_t& version) const;

  // The outlier finder (RenderSession::setOutlierCount): keep the `count` brightest weighted
  // contributions of the full passes from the next one on (0: off, the default). No new
  // generation: the image is the same, its samples take the kernel's recording route (slower).
  // A change of count starts the list again; each new generation starts it at its first pass.
  // Settings without independent bidirectional samples (pt, mlt) publish no list.
  void setOutlierCount(int count);
  // The list after the newest full pass that kept one; false when there is none or nothing newer
  // than `version` (updated on success).
  bool outliers(OutlierList& out, uint64_t& version) const;

  // Per-technique timing (BidirTracer::setTiming) from the next pass on; no new generation.
  void setTiming(bool on);
  // Replaces the pass observer (empty: none); takes effect from the next pass.
  void setPassObserver(PassObserver observer);

  // Blocks until the current generation has at least `spp` full passes (tests, screenshots), or
  // `timeoutSeconds` elapsed; returns whether it got there.
  bool waitForSpp(uint64_t spp, double timeoutSeconds) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace pathlab
