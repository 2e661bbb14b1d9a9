// Passes over tiles with TBB; per-thread counters merged after each pass.
#include "core/render/render_session.h"

#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <stdexcept>

namespace pathlab {

namespace {
constexpr int kTileSize = 16;
// Per-thread splat buffers (SplatBuffer) up to this much memory for all threads together; beyond
// it (many threads and a large image) splats go to the film atomically.
constexpr size_t kMaxThreadSplatBytes = size_t{512} << 20;

const RenderSettings& validated(const RenderSettings& settings, const Scene& scene) {
  validateSettings(settings);
  validateSettingsForCamera(settings, scene.cameraDesc());
  return settings;
}

PassSchedule validated(PassSchedule schedule) {
  if (schedule.stride == 0) throw std::invalid_argument("a pass schedule's stride must be at least 1");
  return schedule;
}
}  // namespace

struct RenderSession::ThreadSplats {
  tbb::enumerable_thread_specific<SplatBuffer> buffers;
  ThreadSplats(int width, int height) : buffers(width, height) {}
};

struct RenderSession::ThreadChecks {
  tbb::enumerable_thread_specific<TechniqueCheck::PassSums> sums;
  explicit ThreadChecks(const TechniqueCheck& check) : sums(TechniqueCheck::PassSums(check)) {}
};

RenderSession::~RenderSession() = default;

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings, PassSchedule schedule)
    : scene_(scene),
      settings_(validated(settings, scene)),
      schedule_(validated(schedule)),
      camera_(settings.camera.value_or(scene.cameraDesc()), settings.width, settings.height, settings.lens),
      pathTracer_(scene, pathTracerOptions(settings)),
      cameraMedium_(scene.mediumAt(camera_.position())),
      film_(settings.width, settings.height) {
  if (settings.integrator != IntegratorKind::Pt) bidirTracer_ = std::make_unique<BidirTracer>(scene, camera_, bidirOptions(settings));
  const size_t threads = static_cast<size_t>(std::max(tbb::this_task_arena::max_concurrency(), 1));
  if (bidirTracer_ && threads * SplatBuffer::bytesFor(settings.width, settings.height) <= kMaxThreadSplatBytes)
    threadSplats_ = std::make_unique<ThreadSplats>(settings.width, settings.height);
  if (bidirTracer_ && settings.pyramidLength > 0)
    pyramid_ = std::make_unique<TechniqueFilms>(settings.width, settings.height, settings.pyramidLength,
                                                settings.techniqueMaps);
  if (bidirTracer_ && settings.checkTechniques) {
    const TechniqueSet enabled = enabledTechniques(settings);
    check_ = std::make_unique<TechniqueCheck>(settings.width, settings.height, settings.maxLength, settings.checkBlocks,
                                              [&](int s, int t) { return enabled.contains(s, t); });
    threadChecks_ = std::make_unique<ThreadChecks>(*check_);
  }
}

Spectrum RenderSession::replaySample(int x, int y, uint64_t pass, Counters& counters, Film* splats,
                                     SampleTrace* trace) const {
  return sampleAt(x, y, pass, SampleTargets{splats, nullptr, trace, SampleId{x, y, pass}}, counters);
}

Pcg32 sampleStream(const RenderSettings& settings, int x, int y, uint64_t pass, RngStream stream) {
  const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(settings.width) + static_cast<uint64_t>(x);
  return makeSampleRng(settings.seed, pixel, pass, stream);
}

Image RenderSession::techniqueImage(int s, int t, bool unweighted) const {
  if (!pyramid_) return Image{film_.width(), film_.height(), std::vector<float>(3 * film_.pixelCount(), 0.f)};
  return pyramid_->readout(s, t, unweighted, film_.samplesPerPixel(), film_.lightSubpaths());
}

std::vector<float> RenderSession::sampleableLuminance(int s, int t) const {
  if (!pyramid_) return std::vector<float>(film_.pixelCount(), 0.f);
  return pyramid_->readoutSampleable(s, t, film_.samplesPerPixel(), film_.lightSubpaths());
}

std::vector<std::span<double>> RenderSession::sums() {
  std::vector<std::span<double>> all;
  for (std::span<double> s : film_.sums()) all.push_back(s);
  if (pyramid_)
    for (std::span<double> s : pyramid_->sums()) all.push_back(s);
  return all;
}

void RenderSession::addForeignPasses(uint64_t passes, const Counters& counters) {
  film_.finishPass(passes, bidirTracer_ ? passes * lightSubpathsPerPass(film_.pixelCount()) : 0);
  counters_ += counters;
}

Spectrum RenderSession::sampleAt(int x, int y, uint64_t pass, const SampleTargets& targets, Counters& counters) const {
  Pcg32 rng = sampleStream(settings_, x, y, pass, RngStream::Camera);
  const Vec2 uFilm = rng.next2D();  // box filter: uniform over the pixel
  const Vec2 uLens = rng.next2D();
  const Vec2 pRaster = Vec2(static_cast<float>(x), static_cast<float>(y)) + uFilm;
  ++counters.cameraSamples;
  if (bidirTracer_) {
    Pcg32 lightRng = sampleStream(settings_, x, y, pass, RngStream::Light);
    SampleOutputs outputs(targets);
    bidirTracer_->sample(pRaster, uLens, rng, lightRng, outputs, counters);
    return outputs.cameraEstimate();
  }
  const Ray ray = camera_.generateRay(pRaster, uLens);
  return pathTracer_.Li(ray, rng, counters, cameraMedium_);
}

bool RenderSession::renderPass(const std::atomic<bool>* cancel) {
  tbb::enumerable_thread_specific<Counters> local;
  pixelsDone_.store(0, std::memory_order_relaxed);
  const uint64_t pass = schedule_.pass(passes_.load(std::memory_order_relaxed));
  const SampleTargets shared{&film_, pyramid_.get(), nullptr, {}};
  std::atomic<bool> cancelled{false};
  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, settings_.height, kTileSize, 0, settings_.width, kTileSize),
      [&](const tbb::blocked_range2d<int>& tile) {
        if (cancel && cancel->load(std::memory_order_relaxed)) {
          cancelled.store(true, std::memory_order_relaxed);
          return;
        }
        Counters& c = local.local();
        SplatBuffer* splats = threadSplats_ ? &threadSplats_->buffers.local() : nullptr;
        TechniqueCheck::PassSums* checkSums = threadChecks_ ? &threadChecks_->sums.local() : nullptr;
        for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
          for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
            SampleTargets targets = shared;
            targets.id = SampleId{x, y, pass};
            targets.splats = splats;
            targets.check = checkSums;
            const Spectrum L = sampleAt(x, y, pass, targets, c);
            if (!film_.addSample(x, y, L)) {
              countDiscarded(L, c);
              c.noteDiscard(DiscardExample{x, y, pass, -1, -1, L});
            }
          }
        pixelsDone_.fetch_add(static_cast<uint64_t>(tile.rows().size() * tile.cols().size()),
                              std::memory_order_relaxed);
      });
  for (const Counters& c : local) counters_ += c;
  if (threadSplats_)
    for (SplatBuffer& b : threadSplats_->buffers) {
      if (cancelled.load()) b.clear();
      else b.mergeInto(film_);
    }
  if (threadChecks_) {
    std::vector<TechniqueCheck::PassSums*> sums;
    for (TechniqueCheck::PassSums& t : threadChecks_->sums) sums.push_back(&t);
    if (cancelled.load()) {
      for (TechniqueCheck::PassSums* t : sums) t->clear();
    } else {
      check_->finishPass(sums);
    }
  }
  if (cancelled.load()) return false;
  film_.finishPass(1, bidirTracer_ ? lightSubpathsPerPass(film_.pixelCount()) : 0);
  passes_.fetch_add(1, std::memory_order_relaxed);
  return true;
}

}  // namespace pathlab
