// The worker loop: take the newest generation's settings, render its previews then full passes,
// publish each finished image; a new generation cancels the pass in flight (between tiles).
#include "core/render/progressive_renderer.h"

#include "core/render/render_session.h"
#include "core/render/technique_luminance.h"

#include <tbb/task_arena.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace pathlab {

namespace {

using Clock = std::chrono::steady_clock;

// The Metropolis chains a viewer's 3D view can draw (the slider's range).
constexpr int kViewerWatchedChains = 8;

// Preview resolutions of a new generation, coarsest first (each 1 sample per pixel).
constexpr int kPreviewFactors[] = {8, 4, 2};

// The same view at 1/factor of the resolution (rounded up: the aspect ratio may differ by less
// than a preview pixel).
RenderSettings previewSettings(const RenderSettings& full, int factor) {
  RenderSettings p = full;
  p.width = (full.width + factor - 1) / factor;
  p.height = (full.height + factor - 1) / factor;
  p.pyramidLength = 0;
  p.techniqueMaps = false;
  p.varianceMaps = false;
  // Metropolis: a preview has factor^2 times fewer pixels, so as many fewer mutations a pass; its
  // bootstrap (what its first image waits for) shrinks alike, to no fewer than 1000 samples.
  p.mlt.bootstrap = std::max<uint64_t>(std::min<uint64_t>(full.mlt.bootstrap, 1000),
                                       full.mlt.bootstrap / static_cast<uint64_t>(factor * factor));
  p.mlt.chains = std::max(1, std::min(full.mlt.chains, (p.width * p.height + 3) / 4));
  return p;
}

}  // namespace

struct ProgressiveRenderer::State {
  explicit State(int threads) : arena(threads > 0 ? threads : tbb::task_arena::automatic) {}

  mutable std::mutex mutex;
  std::condition_variable wake;               // settings, scene, pause, stop changed
  mutable std::condition_variable published;  // a new image was published
  std::shared_ptr<const Scene> scene;
  RenderSettings settings;
  uint64_t generation = 1;
  bool paused = false, stop = false;
  uint64_t targetSpp = 0;
  int thumbnailSide = 128;
  std::atomic<bool> cancel{false};
  bool timing = false;
  int outlierCount = 0;
  std::shared_ptr<const PassObserver> observer;

  uint64_t version = 0;
  RenderSnapshot front;
  std::vector<TechniqueThumbnail> thumbnails;
  uint64_t thumbnailsVersion = 0;
  TechniqueLuminance maps;
  uint64_t mapsVersion = 0;
  OutlierList outliers;
  uint64_t outliersVersion = 0;

  tbb::task_arena arena;
  std::thread worker;

  void run();
};

void ProgressiveRenderer::State::run() {
  uint64_t gen = 0;
  std::shared_ptr<const Scene> sc;
  RenderSettings set;
  std::unique_ptr<RenderSession> session;
  size_t previewStep = 0;
  Counters previewCounters;
  Clock::time_point start;
  int side = 128;
  bool timed = false;
  int wantedOutliers = 0;
  uint64_t outliersFrom = 0;  // the pass the session's outlier finder started at
  std::shared_ptr<const PassObserver> observe;
  double renderSeconds = 0.0;  // sum of the pass durations of this generation

  // Runs one pass in the arena, adding its duration to renderSeconds.
  auto runPass = [&](RenderSession& session) {
    session.setTiming(timed);
    const auto passStart = Clock::now();
    const bool finished = arena.execute([&] { return session.renderPass(&cancel); });
    renderSeconds += std::chrono::duration<double>(Clock::now() - passStart).count();
    return finished;
  };

  auto publish = [&](Image image, bool preview, int factor, const Counters& counters, uint64_t spp,
                     std::shared_ptr<const CheckReport> check, std::shared_ptr<const MltSummary> mlt = nullptr,
                     std::shared_ptr<const LightPathStatus> lightPaths = nullptr) {
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    std::lock_guard lock(mutex);
    if (generation != gen) return;  // superseded while finishing: never shown
    front.image = std::move(image);
    front.generation = gen;
    front.version = ++version;
    front.preview = preview;
    front.previewFactor = factor;
    front.samplesPerPixel = spp;
    front.seconds = seconds;
    front.renderSeconds = renderSeconds;
    front.counters = counters;
    front.settings = set;
    front.check = std::move(check);
    front.mlt = std::move(mlt);
    front.lightPaths = std::move(lightPaths);
    published.notify_all();
  };

  for (;;) {
    {
      std::unique_lock lock(mutex);
      wake.wait(lock, [&] {
        // The target as it is now (targetSpp), not as it was: raising it must wake the worker.
        const bool done = session && targetSpp > 0 && session->passes() >= targetSpp;
        return stop || generation != gen || (!paused && !done);
      });
      if (stop) return;
      if (generation != gen) {
        session.reset();  // before the scene it refers to may be released
        gen = generation;
        sc = scene;
        set = settings;
        cancel.store(false);
        previewStep = 0;
        previewCounters = Counters{};
        start = Clock::now();
        renderSeconds = 0.0;
        thumbnails.clear();
        maps = TechniqueLuminance{};
        outliers = OutlierList{};
        ++mapsVersion;
        ++thumbnailsVersion;
        ++outliersVersion;
      }
      side = thumbnailSide;
      timed = timing;
      wantedOutliers = outlierCount;
      observe = observer;
    }

    if (previewStep < std::size(kPreviewFactors)) {
      const int factor = kPreviewFactors[previewStep++];
      if (set.width < 2 * factor && set.height < 2 * factor) continue;  // no coarser than the image
      RenderSession preview(*sc, previewSettings(set, factor));
      if (!runPass(preview)) continue;
      previewCounters += preview.counters();
      publish(preview.image(), true, factor, previewCounters, 0, nullptr);
      continue;
    }

    if (!session) {
      session = std::make_unique<RenderSession>(*sc, set);
      // The viewer's 3D view draws a few chains as they move (MltSummary::watched).
      if (Metropolis* m = session->metropolis()) m->setWatchedChains(kViewerWatchedChains);
    }
    // The outlier finder starts (again) between passes when its count changed; a cancelled pass
    // leaves the tally with part of a pass, but its generation is dropped with it.
    const int finderCount = session->outliersAvailable() ? wantedOutliers : 0;
    if (finderCount != session->outlierCount()) {
      session->setOutlierCount(finderCount);
      outliersFrom = session->passes();
    }
    if (!runPass(*session)) continue;
    Counters counters = previewCounters;
    counters += session->counters();
    Image image = session->image();
    if (observe && *observe) (*observe)(PassInfo{gen, set, sc.get(), session->passes(), renderSeconds}, image);
    std::shared_ptr<const CheckReport> check;
    if (const TechniqueCheck* c = session->techniqueCheck()) check = std::make_shared<const CheckReport>(checkReport(*c));
    std::shared_ptr<const MltSummary> mlt;
    if (const Metropolis* m = session->metropolis()) mlt = std::make_shared<const MltSummary>(m->summary());
    std::shared_ptr<const LightPathStatus> lightPaths;
    if (const LightPathChoice* l = session->lightPathChoice()) lightPaths = std::make_shared<const LightPathStatus>(l->status());
    publish(std::move(image), false, 1, counters, session->passes(), std::move(check), std::move(mlt),
            std::move(lightPaths));

    if (session->hasPyramid()) {
      {
        std::lock_guard lock(mutex);
        side = thumbnailSide;
      }
      std::vector<TechniqueThumbnail> thumbs = techniqueThumbnails(
          set.pyramidLength, side, [&](Technique x, bool unweighted) { return session->techniqueImage(x, unweighted); },
          session->pyramidFamilies());
      std::lock_guard lock(mutex);
      if (generation == gen) {
        thumbnails = std::move(thumbs);
        ++thumbnailsVersion;
      }
    }
    if (finderCount > 0) {
      OutlierList list{session->outliers(), gen, outliersFrom, session->passes(), set};
      std::lock_guard lock(mutex);
      if (generation == gen) {
        outliers = std::move(list);
        ++outliersVersion;
      }
    }
    if ((set.techniqueMaps || set.varianceMaps) && session->hasPyramid()) {
      TechniqueLuminance lum = techniqueLuminance(*session);
      std::lock_guard lock(mutex);
      if (generation == gen) {
        maps = std::move(lum);
        ++mapsVersion;
      }
    }
  }
}

ProgressiveRenderer::ProgressiveRenderer(std::shared_ptr<const Scene> scene, const RenderSettings& settings,
                                         int threads)
    : state_(std::make_unique<State>(threads)) {
  validateSettings(settings);
  if (scene) validateSettingsForCamera(settings, scene->cameraDesc());
  state_->scene = std::move(scene);
  state_->settings = settings;
  state_->worker = std::thread([s = state_.get()] { s->run(); });
}

ProgressiveRenderer::~ProgressiveRenderer() {
  {
    std::lock_guard lock(state_->mutex);
    state_->stop = true;
    state_->cancel.store(true);
  }
  state_->wake.notify_all();
  state_->worker.join();
}

bool ProgressiveRenderer::setSettings(const RenderSettings& settings) {
  validateSettings(settings);
  {
    std::lock_guard lock(state_->mutex);
    if (state_->scene)
      validateSettingsForCamera(settings, state_->scene->cameraDesc());
    if (settings == state_->settings) return false;
    state_->settings = settings;
    ++state_->generation;
    state_->cancel.store(true);
  }
  state_->wake.notify_all();
  return true;
}

void ProgressiveRenderer::setScene(std::shared_ptr<const Scene> scene, const RenderSettings& settings) {
  validateSettings(settings);
  if (scene) validateSettingsForCamera(settings, scene->cameraDesc());
  {
    std::lock_guard lock(state_->mutex);
    state_->scene = std::move(scene);
    state_->settings = settings;
    ++state_->generation;
    state_->cancel.store(true);
  }
  state_->wake.notify_all();
}

RenderSettings ProgressiveRenderer::settings() const {
  std::lock_guard lock(state_->mutex);
  return state_->settings;
}

std::shared_ptr<const Scene> ProgressiveRenderer::scene() const {
  std::lock_guard lock(state_->mutex);
  return state_->scene;
}

uint64_t ProgressiveRenderer::generation() const {
  std::lock_guard lock(state_->mutex);
  return state_->generation;
}

void ProgressiveRenderer::setPaused(bool paused) {
  {
    std::lock_guard lock(state_->mutex);
    state_->paused = paused;
  }
  state_->wake.notify_all();
}

bool ProgressiveRenderer::paused() const {
  std::lock_guard lock(state_->mutex);
  return state_->paused;
}

void ProgressiveRenderer::setTargetSpp(uint64_t spp) {
  {
    std::lock_guard lock(state_->mutex);
    state_->targetSpp = spp;
  }
  state_->wake.notify_all();
}

void ProgressiveRenderer::setThumbnailSide(int side) {
  std::lock_guard lock(state_->mutex);
  state_->thumbnailSide = std::max(1, side);
}

void ProgressiveRenderer::setTiming(bool on) {
  std::lock_guard lock(state_->mutex);
  state_->timing = on;
}

void ProgressiveRenderer::setOutlierCount(int count) {
  {
    std::lock_guard lock(state_->mutex);
    state_->outlierCount = std::max(0, count);
  }
  state_->wake.notify_all();
}

bool ProgressiveRenderer::outliers(OutlierList& out, uint64_t& version) const {
  std::lock_guard lock(state_->mutex);
  if (state_->outliersVersion <= version) return false;
  out = state_->outliers;
  version = state_->outliersVersion;
  return true;
}

void ProgressiveRenderer::setPassObserver(PassObserver observer) {
  auto shared = observer ? std::make_shared<const PassObserver>(std::move(observer)) : nullptr;
  std::lock_guard lock(state_->mutex);
  state_->observer = std::move(shared);
}

bool ProgressiveRenderer::snapshot(RenderSnapshot& out) const {
  std::lock_guard lock(state_->mutex);
  if (state_->front.version == 0 || state_->front.version <= out.version) return false;
  out = state_->front;
  return true;
}

bool ProgressiveRenderer::pyramid(std::vector<TechniqueThumbnail>& out, uint64_t& version) const {
  std::lock_guard lock(state_->mutex);
  if (state_->thumbnailsVersion <= version) return false;
  out = state_->thumbnails;
  version = state_->thumbnailsVersion;
  return true;
}

bool ProgressiveRenderer::techniqueMaps(TechniqueLuminance& out, uint64_t& version) const {
  std::lock_guard lock(state_->mutex);
  if (state_->mapsVersion <= version) return false;
  out = state_->maps;
  version = state_->mapsVersion;
  return true;
}

bool ProgressiveRenderer::waitForSpp(uint64_t spp, double timeoutSeconds) const {
  std::unique_lock lock(state_->mutex);
  return state_->published.wait_for(lock, std::chrono::duration<double>(timeoutSeconds), [&] {
    return state_->front.generation == state_->generation && state_->front.samplesPerPixel >= spp;
  });
}

}  // namespace pathlab
