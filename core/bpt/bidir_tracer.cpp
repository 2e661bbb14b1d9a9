// BidirTracer: generate both subpaths, evaluate every technique in use, hand the results on.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"
#include "core/metrics/technique_timer.h"

#include <algorithm>

namespace pathlab {

// Per-thread buffers sized once: no allocation per sample.
struct BidirTracer::Walks {
  CameraSubpath camera;
  LightSubpath light;
  SubpathMisSums cameraSums, lightSums;  // MisEvaluation::PartialSums only
  Connection connection;                 // scratch reused by every technique
};

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options)
    : scene_(scene), camera_(camera), options_(options), misPower_(options.mis) {
  options_.pyramidLength = std::min(options_.pyramidLength, options_.maxLength);
  // The partial sums weigh every technique of a path's length: exact only when all are enabled.
  misEvaluation_ = options_.techniques.containsAllUpTo(options_.maxLength) ? MisEvaluation::PartialSums
                                                                          : MisEvaluation::Explicit;
  minConnectionDistance_ = minConnectionDistance(scene, options_.mis);
  // The walks need t camera vertices and s light vertices for technique (s, t), except that s = 1
  // with t >= 2 samples its light vertex afresh (next-event estimation).
  auto need = [&](int s, int t) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, t);
    if (!(s == 1 && t >= 2)) lightVerticesNeeded_ = std::max(lightVerticesNeeded_, s);
  };
  for (const Technique x : techniquesUpTo(options_.maxLength))
    if (options_.techniques.contains(x) || x.length() <= options_.pyramidLength) need(x.s, x.t);
  if (options_.isolate) need(options_.isolate->s, options_.isolate->t);
}

float BidirTracer::weight(const MisPath& path, const Walks& walks, Counters& counters) const {
  const float ratio = lightTracingRatio();
  // The partial sums decline (nullopt) a path with a near-coincident connection: misWeight then
  // applies MisOptions::minConnection.
  const std::optional<float> fast =
      misEvaluation_ == MisEvaluation::PartialSums
          ? misWeightFromSums(scene_, camera_, path, walks.lightSums, walks.cameraSums, misPower_, ratio,
                              minConnectionDistance_)
          : std::nullopt;
  const float w = fast ? *fast : misWeight(scene_, camera_, path, options_.techniques, options_.mis, ratio);
  if (options_.checkMis) {
    ++counters.misPartitionChecks;
    const double sum = misWeightSum(scene_, camera_, path, options_.techniques, options_.mis, ratio);
    if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
  }
  return w;
}

void BidirTracer::evaluate(TechniqueResult& r, bool enabled, bool unweightedInImage, uint64_t connectionKey, Walks& walks,
                           const SampleOutputs& outputs, Counters& counters) const {
  const int s = r.s, t = r.t;
  // Each connection draws its fresh light or lens sample from a stream of its own, keyed by the
  // sample and (s, t): a technique's estimate does not depend on which other techniques are
  // evaluated, so an isolated render, the pyramid and the full image see the same connections.
  Pcg32 rng(mixBits(connectionKey ^ (static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t))), connectionKey);
  Connection& c = walks.connection;
  if (!formConnection(scene_, camera_, walks.light, s, walks.camera, t, rng, c)) return;

  // The weight is computed over the enabled set (a disabled technique's share is zero) before the
  // shadow ray, which is traced only when something will use the contribution.
  if (enabled) {
    const MisPath path{walks.light.data(), s, walks.camera.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
    r.weight = weight(path, walks, counters);
  }
  r.imageWeight = !r.inImage ? 0.f : unweightedInImage ? 1.f : r.weight;
  if (!(r.imageWeight > 0.f) && !r.inPyramid && !outputs.wantsEveryContribution()) {
    r.weight = 0.f;
    return;  // TechniqueOutcome::Zero: nothing would use it, so no shadow ray
  }
  if (needsShadowRay(s)) {
    ++counters.shadowRays;
    if (!unoccluded(scene_, c.shadowRay)) {
      r.outcome = TechniqueOutcome::Blocked;
      return;
    }
  }
  r.outcome = TechniqueOutcome::Contributed;
  r.unweighted = c.L;
  if (t == 1) r.pRaster = c.pRaster;
}

Spectrum BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                             Counters& counters) const {
  // The connections' key is drawn first, so that how long the walks below are allowed to grow
  // changes no connection's random numbers.
  const uint64_t keyHigh = cameraRng.nextU32();  // two statements: operand order is unspecified
  const uint64_t connectionKey = keyHigh << 32 | cameraRng.nextU32();

  // Each walk stops at the longest prefix any technique in use needs (light tracing needs no
  // camera walk at all).
  thread_local Walks walks;
  const bool timed = timing_ && connectionKey % kTimedSampleStride == 0;
  const uint64_t raysBefore = counters.rays;
  const uint64_t walkStart = timed ? ticks() : 0;
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, cameraRng,
                                       WalkOptions{cameraVerticesNeeded_, options_.russianRoulette}, walks.camera,
                                       counters);
  const uint64_t cameraRays = counters.rays, cameraEnd = timed ? ticks() : 0;
  const int ns = lightVerticesNeeded_ > 0
                     ? generateLightSubpath(scene_, lightRng, WalkOptions{lightVerticesNeeded_, options_.russianRoulette},
                                            walks.light, counters)
                     : 0;
  if (misEvaluation_ == MisEvaluation::PartialSums) {
    accumulateCameraSums(walks.camera, misPower_, lightTracingRatio(), walks.cameraSums);
    if (ns > 0) accumulateLightSums(walks.light, misPower_, walks.lightSums);
  }
  counters.cameraWalk.rays += cameraRays - raysBefore;
  counters.lightWalk.rays += counters.rays - cameraRays;
  if (timed) {
    counters.cameraWalk.nanoseconds += elapsedNanoseconds(walkStart, cameraEnd);
    counters.lightWalk.nanoseconds += elapsedNanoseconds(cameraEnd, ticks());
    ++counters.timedSamples;
  }

  const int pyramidLength = targets.pyramid ? options_.pyramidLength : 0;
  if (targets.trace) {
    targets.trace->cameraVertices = nt;
    targets.trace->lightVertices = ns;
    targets.trace->records.clear();
  }
  SampleOutputs outputs(targets, counters);
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= std::max(ns, 1); ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > options_.maxLength) continue;
      if (s > ns && !(s == 1 && t >= 2)) continue;  // next-event estimation needs no light subpath
      const bool enabled = options_.techniques.contains(s, t);
      const std::optional<Isolation>& isolate = options_.isolate;
      const bool isolated = isolate && isolate->s == s && isolate->t == t;
      TechniqueResult r;
      r.s = s;
      r.t = t;
      r.pRaster = pRaster;
      r.inImage = isolate ? isolated && (enabled || isolate->unweighted) : enabled;
      r.inPyramid = k <= pyramidLength;
      if (!r.inImage && !r.inPyramid) continue;

      TechniqueCounters& tc = counters.technique(s, t);
      ++tc.tried;
      const uint64_t shadowBefore = counters.shadowRays;
      ScopedTimer timer(timed, tc.nanoseconds);
      evaluate(r, enabled, isolated && isolate->unweighted, connectionKey, walks, outputs, counters);
      timer.stop();  // what follows is the outputs', not the technique's
      tc.shadowRays += counters.shadowRays - shadowBefore;
      outputs.add(r, tc);
    }
  return outputs.cameraEstimate();
}

}  // namespace pathlab
