// Passes over tiles with TBB; per-thread counters merged after each pass.
#include "core/render/render_session.h"

#include <tbb/blocked_range2d.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace pathlab {

namespace {
constexpr int kTileSize = 16;
}  // namespace

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings)
    : scene_(scene),
      settings_(settings),
      camera_(scene.cameraDesc(), settings.width, settings.height, settings.lens),
      pathTracer_(scene, settings),
      film_(settings.width, settings.height) {
  if (settings.integrator != IntegratorKind::Pt) bidirTracer_ = std::make_unique<BidirTracer>(scene, camera_, settings);
}

Spectrum RenderSession::replaySample(int x, int y, uint64_t pass, Counters& counters) const {
  return sampleAt(x, y, pass, nullptr, counters);
}

Spectrum RenderSession::sampleAt(int x, int y, uint64_t pass, Film* film, Counters& counters) const {
  const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(settings_.width) + static_cast<uint64_t>(x);
  Pcg32 rng = makeSampleRng(settings_.seed, pixel, pass, RngStream::Camera);
  const Vec2 uFilm = rng.next2D();  // box filter: uniform over the pixel
  const Vec2 uLens = rng.next2D();
  const Vec2 pRaster = Vec2(static_cast<float>(x), static_cast<float>(y)) + uFilm;
  ++counters.cameraSamples;
  if (bidirTracer_) {
    Pcg32 lightRng = makeSampleRng(settings_.seed, pixel, pass, RngStream::Light);
    return bidirTracer_->sample(pRaster, uLens, rng, lightRng, film, counters);
  }
  const Ray ray = camera_.generateRay(pRaster, uLens);
  return pathTracer_.Li(ray, rng, counters);
}

void RenderSession::renderPass() {
  tbb::enumerable_thread_specific<Counters> local;
  pixelsDone_.store(0, std::memory_order_relaxed);
  const uint64_t pass = passes_;
  tbb::parallel_for(
      tbb::blocked_range2d<int>(0, settings_.height, kTileSize, 0, settings_.width, kTileSize),
      [&](const tbb::blocked_range2d<int>& tile) {
        Counters& c = local.local();
        for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
          for (int x = tile.cols().begin(); x < tile.cols().end(); ++x) {
            const Spectrum L = sampleAt(x, y, pass, &film_, c);
            if (!film_.addSample(x, y, L)) countDiscarded(L, c);
          }
        pixelsDone_.fetch_add(static_cast<uint64_t>(tile.rows().size() * tile.cols().size()),
                              std::memory_order_relaxed);
      });
  film_.finishPass(1, bidirTracer_ ? lightSubpathsPerPass(film_.pixelCount()) : 0);
  for (const Counters& c : local) counters_ += c;
  ++passes_;
}

}  // namespace pathlab
