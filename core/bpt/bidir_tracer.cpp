// BidirTracer: generate both subpaths, evaluate every technique in use, hand the results on.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"
#include "core/bpt/mis_off.h"
#include "core/bpt/path_techniques.h"
#include "core/counters/technique_timer.h"

#include <algorithm>
#include <type_traits>

namespace pathlab {

// Per-thread buffers sized once: no allocation per sample.
struct BidirTracer::Walks {
  CameraSubpath camera;
  LightSubpath light;
  SubpathMisSums cameraSums, lightSums;  // MisEvaluation::PartialSums only
  Connection connection;                 // scratch reused by every technique
  std::vector<double> densityRatios;     // TechniqueResult::densityRatios, when an output wants them
  std::vector<TechniqueOnPath> onPath;   // TechniqueResult::onPath (replay)
  TracedPath traced;                     // TechniqueResult::traced (replay)
};

const char* connectStrategyName(ConnectStrategy c) { return c == ConnectStrategy::Endpoints ? "endpoints" : "all"; }

namespace {

// ConnectStrategy::Endpoints: the walk streams of technique (s, t), keyed by the sample like its
// connection's stream (evaluate) and salted apart from it and from each other, so each technique's
// subpaths are independent of every other technique's and of which techniques are in use.
constexpr uint64_t kCameraWalkSalt = 0x9E3779B97F4A7C15ull, kLightWalkSalt = 0xC2B2AE3D27D4EB4Full;
Pcg32 walkStream(uint64_t connectionKey, int s, int t, uint64_t salt) {
  const uint64_t st = static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t);
  return Pcg32(mixBits(connectionKey ^ st ^ salt), mixBits(connectionKey + salt));
}

// Each connection draws its fresh light or lens sample from a stream of its own, keyed by the
// sample and (s, t): a technique's estimate does not depend on which other techniques are
// evaluated, so an isolated render, the pyramid and the full image see the same connections. Only
// next-event estimation (s = 1) and light tracing (t = 1) draw from it: the others skip seeding it
// (about 1 % of a sample's instructions).
Pcg32 connectionStream(uint64_t connectionKey, int s, int t) {
  return s == 1 || t == 1
             ? Pcg32(mixBits(connectionKey ^ (static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t))), connectionKey)
             : Pcg32::unseeded();
}

// ScopedTimer's stand-in where nothing is timed: nothing to construct or stop.
struct NoTimer {
  NoTimer(bool, uint64_t&) {}
  void stop() {}
};

}  // namespace

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options)
    : scene_(scene), camera_(camera), options_(options), misPower_(options.mis) {
  options_.pyramidLength = std::min(options_.pyramidLength, options_.maxLength);
  // MIS off weighs by length alone: a table, never the partial sums. Otherwise the partial sums
  // weigh every technique of a path's length: exact only when all are enabled.
  if (options_.mis.heuristic == MisHeuristic::Off) {
    misEvaluation_ = MisEvaluation::Constant;
    offWeights_ = misOffWeights(options_.techniques, options_.maxLength);
  } else {
    misEvaluation_ = options_.techniques.containsAllUpTo(options_.maxLength) ? MisEvaluation::PartialSums
                                                                            : MisEvaluation::Explicit;
  }
  minConnectionDistance_ = minConnectionDistance(scene, options_.mis);
  // runImageOnly's preconditions that settings decide: the partial sums, no media, and nothing that
  // changes a result's weight or contribution (isolation, the MIS check, an injected bias).
  imageOnlyPath_ = misEvaluation_ == MisEvaluation::PartialSums && !scene.hasMedia() && !options_.checkMis &&
                      !options_.isolate && !options_.injectBias;
  cameraMedium_ = scene.mediumAt(camera.position());
  // The walks need t camera vertices and s light vertices for technique (s, t), except that s = 1
  // with t >= 2 samples its light vertex afresh (next-event estimation).
  auto need = [&](int s, int t) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, t);
    if (lightWalkNeeded(s, t)) lightVerticesNeeded_ = std::max(lightVerticesNeeded_, s);
  };
  for (const Technique x : techniquesUpTo(options_.maxLength))
    if (options_.techniques.contains(x) || x.length() <= options_.pyramidLength) need(x.s, x.t);
  if (options_.isolate) need(options_.isolate->s, options_.isolate->t);
}

float BidirTracer::weight(const MisPath& path, const Walks& walks, Counters& counters) const {
  const float ratio = lightTracingRatio();
  float w = 0.f;
  if (misEvaluation_ == MisEvaluation::Constant) {
    w = offWeights_[static_cast<size_t>(path.s + path.t - 1)];
  } else {
    // The partial sums decline (nullopt) a path with a near-coincident connection: misWeight then
    // applies MisOptions::minConnection.
    const std::optional<float> fast =
        misEvaluation_ == MisEvaluation::PartialSums
            ? misWeightFromSums(scene_, camera_, path, walks.lightSums, walks.cameraSums, misPower_, ratio,
                                minConnectionDistance_)
            : std::nullopt;
    w = fast ? *fast : misWeight(scene_, camera_, path, options_.techniques, options_.mis, ratio);
  }
  if (options_.checkMis) {
    // Under MIS off a path some enabled technique cannot sample fails here: that is its bias.
    ++counters.misPartitionChecks;
    const double sum = misWeightSum(scene_, camera_, path, options_.techniques, options_.mis, ratio);
    if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
  }
  return w;
}

void BidirTracer::evaluate(TechniqueResult& r, bool enabled, bool unweightedInImage, uint64_t connectionKey, Walks& walks,
                           const SampleOutputs& outputs, Counters& counters) const {
  const int s = r.s, t = r.t;
  Pcg32 rng = connectionStream(connectionKey, s, t);
  Connection& c = walks.connection;
  if (!formConnection(scene_, camera_, walks.light, s, walks.camera, t, rng, c)) return;

  // The weight is computed over the enabled set (a disabled technique's share is zero) before the
  // shadow ray, which is traced only when something will use the contribution. With every
  // technique enabled and the result in the image the weight is positive unless the connection
  // edge itself is shorter than --min-connection (mis.h UsableTechniques; otherwise only
  // degenerate densities, an overflow say, give zero), so there the shadow ray goes first and a
  // blocked path skips its weight: in the Cornell box 13-17 % of the connections with a shadow ray
  // are blocked. The outputs and counters see the same results.
  const MisPath path{walks.light.data(), s, walks.camera.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
  const bool shortConnection = s >= 1 && c.edgeLength2 < minConnectionDistance_ * minConnectionDistance_;
  const bool visibilityFirst = misEvaluation_ == MisEvaluation::PartialSums && r.inImage && !options_.checkMis &&
                               !outputs.wantsOnPath() && !outputs.wantsEveryContribution() && !shortConnection;
  // Whether the weighed result is used; false leaves it TechniqueOutcome::Zero.
  auto weigh = [&] {
    if (enabled) r.weight = weight(path, walks, counters);
    r.imageWeight = !r.inImage ? 0.f : unweightedInImage ? 1.f : r.weight;
    if (!(r.imageWeight > 0.f) && !r.inPyramid && !outputs.wantsEveryContribution()) {
      r.weight = 0.f;
      return false;  // nothing would use it, so no shadow ray
    }
    return true;
  };
  if (!visibilityFirst) {
    const bool used = weigh();
    if (outputs.wantsOnPath()) {
      // The inspector shows blocked paths too: what each technique would have made of them.
      tracePath(scene_, camera_, path, walks.traced);
      r.traced = &walks.traced;
      walks.onPath = techniquesOnPath(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio());
      r.onPath = &walks.onPath;
    }
    if (!used) return;
  }
  if (needsShadowRay(s)) {
    ++counters.shadowRays;
    if (scene_.hasMedia()) {
      // The connection edge's transmittance through the media it crosses (the seed's T_r).
      const Spectrum T = transmittance(scene_, c.shadowRay);
      if (isBlack(T)) {
        r.outcome = TechniqueOutcome::Blocked;
        return;
      }
      c.L *= T;
    } else if (!unoccluded(scene_, c.shadowRay)) {
      r.outcome = TechniqueOutcome::Blocked;
      return;
    }
  }
  if (visibilityFirst && !weigh()) return;
  r.outcome = TechniqueOutcome::Contributed;
  r.unweighted = c.L;
  if (options_.injectBias && options_.injectBias->s == s && options_.injectBias->t == t)
    r.unweighted *= options_.injectBias->factor;  // a deliberately wrong technique (BiasInjection)
  if (outputs.wantsSampleable()) r.sampleableBy = sampleableTechniques(path);
  if (outputs.wantsDensityRatios()) {
    walks.densityRatios.resize(static_cast<size_t>(s + t));
    techniqueDensityRatios(scene_, camera_, path, walks.densityRatios.data());
    r.densityRatios = walks.densityRatios.data();
  }
  if (t == 1) r.pRaster = c.pRaster;
}

template <bool kTimed>
void BidirTracer::runImageOnly(int s, int t, uint64_t connectionKey, Walks& walks, SampleOutputs& outputs,
                               Counters& counters) const {
  TechniqueCounters& tc = counters.technique(s, t);
  ++tc.tried;
  // As run(): the technique's time is its connection, shadow ray and weight, not the output. A
  // template on it, so that untimed samples carry no timer at all (even a ScopedTimer that is off
  // cost 0.4 % of a sample's instructions here).
  std::conditional_t<kTimed, ScopedTimer, NoTimer> timer(kTimed, tc.nanoseconds);
  Connection& c = walks.connection;
  // Interior connections (about half of a Cornell-box sample's) skip formConnection's and the
  // partial sums' dispatch on s, t and the fresh endpoint.
  const bool interior = s >= 2 && t >= 2;
  bool formed;
  if (interior) {
    c.hasSampled = false;  // as formConnection leaves it: no endpoint drawn afresh
    formed = formInteriorConnection(scene_, walks.light, s, walks.camera, t, c);
  } else {
    Pcg32 rng = connectionStream(connectionKey, s, t);
    formed = formConnection(scene_, camera_, walks.light, s, walks.camera, t, rng, c);
  }
  if (!formed) {
    ++tc.zero;
    return;
  }
  // As evaluate(): the shadow ray first, unless the connection edge is shorter than
  // --min-connection; a weight of zero (the explicit weight's near-coincident rule, an overflow)
  // leaves the result zero.
  const bool shortConnection = s >= 1 && c.edgeLength2 < minConnectionDistance_ * minConnectionDistance_;
  float w = 0.f;
  auto weigh = [&] {
    const MisPath path{walks.light.data(), s, walks.camera.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
    const std::optional<float> fast =
        interior ? misWeightInterior(scene_, walks.light, s, walks.camera, t, c.pdfs, c.edgeLength2, walks.lightSums,
                                     walks.cameraSums, misPower_, lightTracingRatio(), minConnectionDistance_)
                 : misWeightFromSums(scene_, camera_, path, walks.lightSums, walks.cameraSums, misPower_,
                                     lightTracingRatio(), minConnectionDistance_);
    w = fast ? *fast : misWeight(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio());
    return w > 0.f;
  };
  if (shortConnection && !weigh()) {
    ++tc.zero;
    return;
  }
  if (needsShadowRay(s)) {
    ++counters.shadowRays;
    ++tc.shadowRays;
    if (!unoccluded(scene_, c.shadowRay)) {
      ++tc.blocked;
      return;
    }
  }
  if (!shortConnection && !weigh()) {
    ++tc.zero;
    return;
  }
  timer.stop();
  outputs.addToImage(s, t, c.pRaster, c.L, w, tc);
}

// prepare and run are inlined into both sample loops: as calls they cost 3 % more instructions
// per path-reuse sample (callgrind).
[[gnu::always_inline]] inline bool BidirTracer::prepare(TechniqueResult& r, int s, int t, Vec2 pRaster,
                                                        int pyramidLength) const {
  const bool enabled = options_.techniques.contains(s, t);
  const std::optional<Isolation>& isolate = options_.isolate;
  const bool isolated = isolate && isolate->s == s && isolate->t == t;
  r.s = s;
  r.t = t;
  r.pRaster = pRaster;
  r.inImage = isolate ? isolated && (enabled || isolate->unweighted) : enabled;
  r.inPyramid = s + t - 1 <= pyramidLength;
  return r.inImage || r.inPyramid;
}

[[gnu::always_inline]] inline void BidirTracer::run(TechniqueResult& r, uint64_t connectionKey, bool timed,
                                                     Walks& walks, SampleOutputs& outputs, Counters& counters) const {
  const std::optional<Isolation>& isolate = options_.isolate;
  const bool unweighted = isolate && isolate->unweighted && isolate->s == r.s && isolate->t == r.t;
  TechniqueCounters& tc = counters.technique(r.s, r.t);
  ++tc.tried;
  const uint64_t shadowBefore = counters.shadowRays;
  ScopedTimer timer(timed, tc.nanoseconds);
  evaluate(r, options_.techniques.contains(r.s, r.t), unweighted, connectionKey, walks, outputs, counters);
  timer.stop();  // what follows is the outputs', not the technique's
  tc.shadowRays += counters.shadowRays - shadowBefore;
  outputs.add(r, tc);
}

int BidirTracer::walkCamera(Vec2 pRaster, Vec2 uLens, int vertices, Pcg32& rng, Walks& walks, Counters& counters) const {
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, rng,
                                       WalkOptions{vertices, options_.russianRoulette, cameraMedium_}, walks.camera, counters);
  if (misEvaluation_ == MisEvaluation::PartialSums) accumulateCameraSums(walks.camera, misPower_, lightTracingRatio(), walks.cameraSums);
  return nt;
}

int BidirTracer::walkLight(int vertices, Pcg32& rng, Walks& walks, Counters& counters) const {
  if (vertices <= 0) return 0;
  const int ns = generateLightSubpath(scene_, rng, WalkOptions{vertices, options_.russianRoulette}, walks.light, counters);
  if (ns > 0 && misEvaluation_ == MisEvaluation::PartialSums) accumulateLightSums(walks.light, misPower_, walks.lightSums);
  return ns;
}

int BidirTracer::traceLightSubpath(Pcg32& lightRng, std::vector<PathVertex>& out, Counters& counters) const {
  thread_local Walks walks;
  const int ns = lightVerticesNeeded_ > 0 ? walkLight(lightVerticesNeeded_, lightRng, walks, counters) : 0;
  out.assign(walks.light.data(), walks.light.data() + ns);
  return ns;
}

Spectrum BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                             Counters& counters) const {
  // The connections' key is drawn first, so that how long the walks below are allowed to grow
  // changes no connection's random numbers.
  const uint64_t keyHigh = cameraRng.nextU32();  // two statements: operand order is unspecified
  const uint64_t connectionKey = keyHigh << 32 | cameraRng.nextU32();

  thread_local Walks walks;
  const bool timed = timing_ && connectionKey % kTimedSampleStride == 0;
  if (timed) ++counters.timedSamples;
  const int pyramidLength = targets.pyramid ? options_.pyramidLength : 0;
  SampleOutputs outputs(targets, counters);
  if (options_.connect == ConnectStrategy::Endpoints) {
    sampleEndpoints(pRaster, uLens, connectionKey, timed, pyramidLength, walks, outputs, targets, counters);
    return outputs.cameraEstimate();
  }

  // Each walk stops at the longest prefix any technique in use needs (light tracing needs no
  // camera walk at all).
  const uint64_t raysBefore = counters.rays;
  const uint64_t walkStart = timed ? ticks() : 0;
  const int nt = walkCamera(pRaster, uLens, cameraVerticesNeeded_, cameraRng, walks, counters);
  const uint64_t cameraRays = counters.rays, cameraEnd = timed ? ticks() : 0;
  const int ns = walkLight(lightVerticesNeeded_, lightRng, walks, counters);
  counters.cameraWalk.rays += cameraRays - raysBefore;
  counters.lightWalk.rays += counters.rays - cameraRays;
  if (timed) {
    counters.cameraWalk.nanoseconds += elapsedNanoseconds(walkStart, cameraEnd);
    counters.lightWalk.nanoseconds += elapsedNanoseconds(cameraEnd, ticks());
  }

  if (targets.trace) {
    targets.trace->cameraVertices = nt;
    targets.trace->lightVertices = ns;
    targets.trace->records.clear();
    targets.trace->onPath.clear();
    targets.trace->paths.clear();
    targets.trace->cameraSubpath.assign(walks.camera.data(), walks.camera.data() + nt);
    targets.trace->lightSubpath.assign(walks.light.data(), walks.light.data() + ns);
  }
  // Per sample, the rest of runImageOnly's preconditions: only the image reads the results (per
  // technique: not in the pyramid).
  const bool imageOnly = imageOnlyPathActive() && outputs.imageOnly();
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= std::max(ns, 1); ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > options_.maxLength) continue;
      if (s > ns && lightWalkNeeded(s, t)) continue;
      if (imageOnly && k > pyramidLength) {
        if (timed) {
          runImageOnly<true>(s, t, connectionKey, walks, outputs, counters);
        } else {
          runImageOnly<false>(s, t, connectionKey, walks, outputs, counters);
        }
        continue;
      }
      TechniqueResult r;
      if (!prepare(r, s, t, pRaster, pyramidLength)) continue;
      if (s == 0 && walks.camera[t - 1].light < 0 && !timed && !targets.trace) {
        // The camera subpath's own vertex is no emitter: formConnection would refuse (s = 0), so
        // the try is counted as run() would count it, without its machinery (one try in seven
        // in the Cornell box).
        TechniqueCounters& tc = counters.technique(s, t);
        ++tc.tried;
        ++tc.zero;
        continue;
      }
      run(r, connectionKey, timed, walks, outputs, counters);
    }
  return outputs.cameraEstimate();
}

void BidirTracer::sampleEndpoints(Vec2 pRaster, Vec2 uLens, uint64_t connectionKey, bool timed, int pyramidLength,
                                  Walks& walks, SampleOutputs& outputs, const SampleTargets& targets,
                                  Counters& counters) const {
  // The seed's naive BPT: for each technique a light subpath of exactly s and a camera subpath of
  // exactly t vertices, sampled independently (every camera subpath through the sample's pRaster
  // and uLens), joined at their endpoints only. The weights are functions of the path alone, so
  // they are those of path reuse and still a partition of unity; the partial sums are those of the
  // technique's own subpaths. The walks' rays and time go to the technique's own row.
  if (targets.trace) {
    targets.trace->cameraVertices = targets.trace->lightVertices = 0;
    targets.trace->records.clear();
    targets.trace->onPath.clear();
    targets.trace->paths.clear();
    targets.trace->cameraSubpath.clear();
    targets.trace->lightSubpath.clear();
  }
  for (const Technique x : techniquesUpTo(options_.maxLength)) {
    TechniqueResult r;
    if (!prepare(r, x.s, x.t, pRaster, pyramidLength)) continue;
    TechniqueCounters& tc = counters.technique(x);
    const uint64_t raysBefore = counters.rays;
    ScopedTimer walkTimer(timed, tc.nanoseconds);
    Pcg32 cameraRng = walkStream(connectionKey, x.s, x.t, kCameraWalkSalt);
    const int nt = walkCamera(pRaster, uLens, x.t, cameraRng, walks, counters);
    int ns = 0;
    if (nt == x.t && lightWalkNeeded(x.s, x.t)) {
      Pcg32 lightRng = walkStream(connectionKey, x.s, x.t, kLightWalkSalt);
      ns = walkLight(x.s, lightRng, walks, counters);
    }
    walkTimer.stop();
    tc.walkRays += counters.rays - raysBefore;
    if (targets.trace) {
      targets.trace->cameraVertices = std::max(targets.trace->cameraVertices, nt);
      targets.trace->lightVertices = std::max(targets.trace->lightVertices, ns);
    }
    if (nt < x.t || (lightWalkNeeded(x.s, x.t) && ns < x.s)) continue;  // a walk ended early
    run(r, connectionKey, timed, walks, outputs, counters);
  }
}

}  // namespace pathlab
