// BidirTracer: generate, connect, weigh, accumulate.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"

#include <algorithm>
#include <chrono>
#include <thread>
#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace pathlab {

namespace {

// Timing reads the time-stamp counter: 15 ns a read on the reference VM against 35 ns for
// steady_clock, which halves what timing costs (constant_tsc: it ticks at one rate on every core).
// Converted to nanoseconds with a factor measured once against steady_clock.
#if defined(__x86_64__)
uint64_t ticks() { return __rdtsc(); }
double nanosecondsPerTick() {
  static const double factor = [] {
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t c0 = __rdtsc();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const auto t1 = std::chrono::steady_clock::now();
    const uint64_t c1 = __rdtsc();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(std::max<uint64_t>(c1 - c0, 1));
  }();
  return factor;
}
#else
uint64_t ticks() {
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
}
double nanosecondsPerTick() { return 1.0; }
#endif

// One camera sample in this many is timed, picked by the sample's own random key: the shares of
// the walks and the techniques are estimated without bias from an eighth of the samples (tens of
// thousands a pass at viewer resolutions), and timing costs an eighth of what timing every sample
// would (about 11% of a bidirectional pass, measured; see docs/benchmarks.md).
constexpr uint64_t kTimedSampleStride = 8;

// Nanoseconds between two tick readings; 0 if the thread moved to a core whose counter lags.
uint64_t elapsedNanoseconds(uint64_t start, uint64_t end) {
  return end > start ? static_cast<uint64_t>(static_cast<double>(end - start) * nanosecondsPerTick()) : 0;
}

// Adds the time from construction to stop() (or to the end of the scope, for the early exits of a
// technique) to `total`, only when timing is on.
class TechniqueTimer {
 public:
  TechniqueTimer(bool on, uint64_t& total) : total_(on ? &total : nullptr), start_(on ? ticks() : 0) {}
  ~TechniqueTimer() { stop(); }
  void stop() {
    if (total_) *total_ += elapsedNanoseconds(start_, ticks());
    total_ = nullptr;
  }

 private:
  uint64_t* total_;
  uint64_t start_;
};

}  // namespace

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const RenderSettings& settings)
    : scene_(scene),
      camera_(camera),
      maxLength_(settings.maxLength),
      russianRoulette_(settings.russianRoulette),
      techniques_(enabledTechniques(settings)),
      mis_(settings.mis),
      isolate_(settings.isolate),
      pyramidLength_(std::min(settings.pyramidLength, settings.maxLength)),
      checkMis_(settings.checkMis) {
  // The walks need t camera vertices and s light vertices for technique (s, t), except that s = 1
  // with t >= 2 samples its light vertex afresh (next-event estimation).
  auto need = [&](int s, int t) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, t);
    if (!(s == 1 && t >= 2)) lightVerticesNeeded_ = std::max(lightVerticesNeeded_, s);
  };
  for (int k = 1; k <= maxLength_; ++k)
    for (int s = 0; s <= k; ++s)
      if (techniques_.contains(s, k + 1 - s) || k <= pyramidLength_) need(s, k + 1 - s);
  if (isolate_) need(isolate_->s, isolate_->t);
}

Spectrum BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                             Counters& counters) const {
  // Each connection draws its fresh light or lens sample from a stream of its own, keyed by the
  // sample and (s, t): a technique's estimate does not depend on which other techniques are
  // evaluated, so an isolated render, the pyramid and the full image see the same connections.
  // Drawn first, so that how long the walks below are allowed to grow changes nothing either.
  const uint64_t keyHigh = cameraRng.nextU32();  // two statements: operand order is unspecified
  const uint64_t connectionKey = keyHigh << 32 | cameraRng.nextU32();

  // Per-thread buffers sized once: no allocation per sample. Each walk stops at the longest
  // prefix any technique in use needs (light tracing needs no camera walk at all).
  thread_local CameraSubpath cameraPath;
  thread_local LightSubpath lightPath;
  const bool timed = timing_ && connectionKey % kTimedSampleStride == 0;
  const uint64_t raysBefore = counters.rays;
  const uint64_t walkStart = timed ? ticks() : 0;
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, cameraRng,
                                       WalkOptions{cameraVerticesNeeded_, russianRoulette_}, cameraPath, counters);
  const uint64_t cameraRays = counters.rays, cameraEnd = timed ? ticks() : 0;
  const int ns = lightVerticesNeeded_ > 0
                     ? generateLightSubpath(scene_, lightRng, WalkOptions{lightVerticesNeeded_, russianRoulette_},
                                            lightPath, counters)
                     : 0;
  counters.cameraWalk.rays += cameraRays - raysBefore;
  counters.lightWalk.rays += counters.rays - cameraRays;
  if (timed) {
    counters.cameraWalk.nanoseconds += elapsedNanoseconds(walkStart, cameraEnd);
    counters.lightWalk.nanoseconds += elapsedNanoseconds(cameraEnd, ticks());
    ++counters.timedSamples;
  }

  const int pyramidLength = targets.pyramid ? pyramidLength_ : 0;
  if (targets.trace) {
    targets.trace->cameraVertices = nt;
    targets.trace->lightVertices = ns;
    targets.trace->records.clear();
  }
  auto discard = [&](const Spectrum& value, int s, int t, TechniqueCounters& tc) {
    countDiscarded(value, tc.discarded);
    counters.noteDiscard(DiscardExample{targets.id.x, targets.id.y, targets.id.sample, s, t, value});
  };
  Spectrum L(0.f);
  const float ratio = lightTracingRatio();
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= std::max(ns, 1); ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > maxLength_) continue;
      if (s > ns && !(s == 1 && t >= 2)) continue;  // next-event estimation needs no light subpath
      const bool enabled = techniques_.contains(s, t);
      const bool isolated = isolate_ && isolate_->s == s && isolate_->t == t;
      const bool inImage = isolate_ ? isolated && (enabled || isolate_->unweighted) : enabled;
      const bool inPyramid = k <= pyramidLength;
      if (!inImage && !inPyramid) continue;

      TechniqueCounters& tc = counters.technique(s, t);
      ++tc.tried;
      TechniqueTimer timer(timed, tc.nanoseconds);
      Pcg32 connectionRng(mixBits(connectionKey ^ (static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t))),
                          connectionKey);
      const uint64_t shadowBefore = counters.shadowRays;
      const Connection c = connect(scene_, camera_, lightPath, s, cameraPath, t, connectionRng, counters);
      tc.shadowRays += counters.shadowRays - shadowBefore;
      if (isBlack(c.L)) {
        ++(c.blocked ? tc.blocked : tc.zero);
        if (targets.trace) targets.trace->records.push_back({s, t, c.L, 0.f, pRaster, c.blocked, false});
        continue;
      }
      ++tc.contributed;
      if (!isValidContribution(c.L)) {
        discard(c.L, s, t, tc);
        continue;
      }
      // The weight is computed over the enabled set; a disabled technique's share is zero.
      float w = 0.f;
      if (enabled) {
        const MisPath path{lightPath.data(), s, cameraPath.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
        w = misWeight(scene_, camera_, path, techniques_, mis_, ratio);
        if (checkMis_) {
          ++counters.misPartitionChecks;
          const double sum = misWeightSum(scene_, camera_, path, techniques_, mis_, ratio);
          if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
        }
      }
      timer.stop();  // what follows is the film's and the pyramid's, not the technique's
      if (targets.trace)
        targets.trace->records.push_back({s, t, c.L, w, t == 1 ? c.pRaster : pRaster, false, inImage});
      const Spectrum weighted = c.L * w;
      if (inPyramid) targets.pyramid->add(s, t, t == 1 ? c.pRaster : pRaster, weighted, c.L);
      if (!inImage) continue;
      const Spectrum contribution = isolated && isolate_->unweighted ? c.L : weighted;
      if (isBlack(contribution)) continue;
      if (t == 1) {
        if (targets.film && !targets.film->splat(c.pRaster, contribution)) discard(contribution, s, t, tc);
      } else {
        L += contribution;
      }
    }
  return L;
}

}  // namespace pathlab
