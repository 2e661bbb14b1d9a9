// BidirTracer: generate both subpaths, evaluate every technique in use once, into the sample's sink.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"
#include "core/bpt/equiangular_technique.h"
#include "core/bpt/merge_sampleable.h"
#include "core/bpt/mis_off.h"
#include "core/bpt/path_techniques.h"
#include "core/counters/technique_tally.h"
#include "core/merge/room.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <type_traits>

namespace pathlab {

// Per-thread buffers sized once: no allocation per sample.
struct BidirTracer::Walks {
  CameraSubpath camera;
  LightSubpath light;
  SubpathMisSums cameraSums, lightSums;  // MisEvaluation::PartialSums only
  Connection connection;                 // scratch reused by every technique
  std::vector<PathVertex> equiangularCamera;  // E(1, t)'s camera prefix, its own vertex last
  std::vector<double> densityRatios;     // TechniqueResult::densityRatios, when an output wants them
  std::vector<double> balanceWeights;    // TechniqueResult::balanceWeights, when an output wants them
  std::vector<TechniqueOnPath> onPath;   // TechniqueResult::onPath (replay)
  TracedPath traced;                     // TechniqueResult::traced (replay)
};

const char* connectStrategyName(ConnectStrategy c) { return c == ConnectStrategy::Endpoints ? "endpoints" : "all"; }
const char* mergeSiteName(MergeSite m) { return m == MergeSite::FirstNonSpecular ? "first-non-specular" : "every"; }

namespace {

// ConnectStrategy::Endpoints: the walk streams of technique (s, t), keyed by the sample like its
// connection's stream (evaluate) and salted apart from it and from each other, so each technique's
// subpaths are independent of every other technique's and of which techniques are in use.
constexpr uint64_t kCameraWalkSalt = 0x9E3779B97F4A7C15ull, kLightWalkSalt = 0xC2B2AE3D27D4EB4Full;
Pcg32 walkStream(uint64_t connectionKey, int s, int t, uint64_t salt) {
  const uint64_t st = static_cast<uint64_t>(s) << 32 | static_cast<uint64_t>(t);
  return Pcg32(mixBits(connectionKey ^ st ^ salt), mixBits(connectionKey + salt));
}

// The replay trace's view of the merges of a pass: none without a pass.
std::optional<MergesOnPath> mergesOnPath(const MergePass* pass, MergeSite site) {
  if (!pass) return std::nullopt;
  return MergesOnPath{MergeMis{pass->eta(), site == MergeSite::FirstNonSpecular, pass->nonCaustic}, pass->radius};
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

// E(1, n-1) can sample the path x0 x1 x2 ... of a connection (equiangular_technique.h).
bool equiangularCanSampleAt(const Scene& scene, const MisPath& path) {
  const int s = path.s, n = s + path.t;
  if (n < 3) return false;
  auto vertex = [&](int i) -> const PathVertex& { return i < s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i); };
  return vertex(1).type == VertexType::Medium && equiangularFactor(scene, vertex(0), vertex(1), vertex(2)) > 0.0;
}

// E(1, k)'s bit in a TechniqueResult::sampleableBy (its slot 2k), none past the mask's 64 bits.
uint64_t equiangularSlotBit(int k) {
  const int slot = Technique::equiangular(k).slot();
  return slot < 64 ? uint64_t{1} << slot : 0;
}

// E(1, t)'s light point and vertex, from a stream of its own keyed as connectionStream's and
// salted apart from C(1, t)'s.
constexpr uint64_t kEquiangularSalt = 0xD6E8FEB86659FD93ull;
Pcg32 equiangularStream(uint64_t connectionKey, int t) {
  const uint64_t key = connectionKey ^ kEquiangularSalt;
  return Pcg32(mixBits(key ^ (uint64_t{1} << 32 | static_cast<uint64_t>(t))), key);
}

}  // namespace

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options)
    : scene_(scene), camera_(camera), options_(options), misPower_(options.mis) {
  options_.pyramidLength = std::min(options_.pyramidLength, options_.maxLength);
  // The equiangular family runs with path reuse and without merges, where the scene has a medium
  // it can sample; elsewhere no weight counts it (validateSettings refuses asking for it there).
  equiangular_ = equiangularFamilySampled(scene, options_);
  if (!equiangular_) options_.mis.mediumSampling = MediumSampling::Distance;
  // MIS off weighs by length alone: a table, never the partial sums. Otherwise the partial sums
  // weigh every technique of a path's length: exact only when all are enabled.
  if (options_.mis.heuristic == MisHeuristic::Off) {
    misEvaluation_ = MisEvaluation::Constant;
    offWeights_ = misOffWeights(options_.techniques, options_.maxLength, options_.mis.mediumSampling);
  } else {
    misEvaluation_ = options_.techniques.containsAllUpTo(options_.maxLength) ? MisEvaluation::PartialSums
                                                                            : MisEvaluation::Explicit;
  }
  // With merges the partial sums count them too (mis_partial_sums.h MergeTerms) when each family
  // is enabled whole or not at all; otherwise every weight is the explicit one over both families
  // (merge_mis.h), MIS off included (its 1 / n_k counts the merges of the length).
  // An isolated merge needs the pass's store even when no merge is enabled (--unweighted).
  merges_ = covers(options_.techniques.families(), TechniqueKind::Merge) ||
            (options_.isolate && options_.isolate->kind == TechniqueKind::Merge);
  if (merges_) {
    const bool anyConnection = covers(options_.techniques.families(), TechniqueKind::Connection);
    const bool allConnections = options_.techniques.containsAllUpTo(options_.maxLength);
    const bool allMerges = options_.techniques.containsAllUpTo(options_.maxLength, TechniqueFamilies::Merges);
    connectionsInSums_ = allConnections ? 1.0 : 0.0;
    // Variance-aware factors reach the partial sums of connections only (mis_partial_sums.h).
    if (misEvaluation_ != MisEvaluation::Constant && options_.mis.heuristic == MisHeuristic::VarianceAware)
      misEvaluation_ = MisEvaluation::Explicit;
    else if (misEvaluation_ != MisEvaluation::Constant)
      misEvaluation_ = allMerges && (allConnections || !anyConnection) && options_.mergeSite == MergeSite::Every
                           ? MisEvaluation::PartialSums
                           : MisEvaluation::Explicit;
  }
  minConnectionDistance_ = minConnectionDistance(scene, options_.mis);
  setLightPaths(options_.lightPaths);
  // The image-only route's preconditions that settings decide: the partial sums, no media, and nothing that
  // changes a result's weight or contribution (isolation, the MIS check, an injected bias).
  imageOnlyPath_ = misEvaluation_ == MisEvaluation::PartialSums && !merges_ && !scene.hasMedia() && !options_.checkMis &&
                      !options_.isolate && !options_.injectBias && !equiangular_;  // its sums know no E(1, k)
  cameraMedium_ = scene.mediumAt(camera.position());
  // The walks need t camera vertices and s light vertices for technique (s, t), except that s = 1
  // with t >= 2 samples its light vertex afresh (next-event estimation).
  auto need = [&](int s, int t) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, t);
    if (lightWalkNeeded(s, t)) lightVerticesNeeded_ = std::max(lightVerticesNeeded_, s);
  };
  // E(1, t) needs C(1, t)'s walk: the ray z(t-2) shot toward z(t-1).
  const TechniqueFamilies walked =
      equiangular_ ? TechniqueFamilies::Connections | TechniqueFamilies::Equiangular : TechniqueFamilies::Connections;
  for (const Technique x : techniquesUpTo(options_.maxLength, walked))
    if (options_.techniques.contains(x) || x.length() <= options_.pyramidLength) need(x.s, x.t);
  // A merge M(s, t) uses t camera vertices and s light vertices.
  if (merges_)
    for (const Technique x : techniquesUpTo(options_.maxLength, TechniqueFamilies::Merges))
      if (options_.techniques.contains(x) || x.length() <= options_.pyramidLength) {
        cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, x.t);
        lightVerticesNeeded_ = std::max(lightVerticesNeeded_, x.s);
      }
  if (options_.isolate && options_.isolate->kind == TechniqueKind::Merge) {
    cameraVerticesNeeded_ = std::max(cameraVerticesNeeded_, options_.isolate->t);
    lightVerticesNeeded_ = std::max(lightVerticesNeeded_, options_.isolate->s);
  } else if (options_.isolate) {
    need(options_.isolate->s, options_.isolate->t);
  }
}

// Inlined (twice) into evaluate: the image-only route's preconditions (the partial sums, no MIS
// check) are compile-time there, so it weighs with the sums alone, as a call cost 2 % more
// instructions per sample (callgrind).
template <bool kRecords>
[[gnu::always_inline]] inline float BidirTracer::weight(const MisPath& path, const Connection& c, const Walks& walks,
                                                        const float* factors, Counters& counters) const {
  const float ratio = lightTracingRatio();
  const int s = path.s, t = path.t;
  if (kRecords && merges_) {
    if (!mergePass_) return misWeight(scene_, camera_, path, options_.techniques, options_.mis, ratio, factors);
    const MergeMis merge{mergePass_->eta(), options_.mergeSite == MergeSite::FirstNonSpecular, mergePass_->nonCaustic};
    if (options_.checkMis) {
      ++counters.misPartitionChecks;
      const double sum = weightSumWithMerges(scene_, camera_, path, options_.techniques, options_.mis, ratio,
                                             minConnectionDistance_, merge, factors);
      if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
    }
    if (misEvaluation_ == MisEvaluation::PartialSums) {
      const MergeTerms terms = mergeTerms(*mergePass_);
      const std::optional<float> fast =
          s >= 2 && t >= 2 ? misWeightInterior(scene_, walks.light, s, walks.camera, t, c.pdfs, c.edgeLength2,
                                               walks.lightSums, walks.cameraSums, misPower_, ratio,
                                               minConnectionDistance_, terms)
                           : misWeightFromSums(scene_, camera_, path, walks.lightSums, walks.cameraSums, misPower_,
                                               ratio, minConnectionDistance_, terms);
      if (fast) return *fast;
    }
    return weightWithMerges(scene_, camera_, path, Technique{s, t}, options_.techniques, options_.mis, ratio,
                            minConnectionDistance_, merge, factors);
  }
  if (kRecords && misEvaluation_ == MisEvaluation::Constant) return offWeights_[static_cast<size_t>(s + t - 1)];
  // The partial sums decline (nullopt) a path with a near-coincident connection: misWeight then
  // applies MisOptions::minConnection. An interior connection (s, t >= 2, about half of a
  // Cornell-box sample's) takes the sums' form without their dispatch on s and t, the same bits
  // (MisPartialSums.* in the tests).
  // The partial sums know no equiangular technique: a path E can sample takes the explicit weight.
  std::optional<float> fast;
  if (!kRecords || (misEvaluation_ == MisEvaluation::PartialSums && !(equiangular_ && equiangularCanSampleAt(scene_, path))))
    fast = s >= 2 && t >= 2
               ? misWeightInterior(scene_, walks.light, s, walks.camera, t, c.pdfs, c.edgeLength2, walks.lightSums,
                                   walks.cameraSums, misPower_, ratio, minConnectionDistance_, factors)
               : misWeightFromSums(scene_, camera_, path, walks.lightSums, walks.cameraSums, misPower_, ratio,
                                   minConnectionDistance_, factors);
  const float w =
      fast ? *fast : misWeight(scene_, camera_, path, options_.techniques, options_.mis, ratio, factors);
  if (kRecords && options_.checkMis) {
    // Under MIS off a path some enabled technique cannot sample fails here: that is its bias.
    ++counters.misPartitionChecks;
    const double sum = misWeightSum(scene_, camera_, path, options_.techniques, options_.mis, ratio, factors);
    if (!(std::abs(sum - 1.0) < 1e-3)) ++counters.misPartitionFailures;
  }
  return w;
}

// Inlined into both sample loops: as calls, prepare and run cost 3 % more instructions per
// path-reuse sample (callgrind, session 11).
[[gnu::always_inline]] inline BidirTracer::TechniqueUse BidirTracer::techniqueUse(int s, int t,
                                                                                 int pyramidLength) const {
  const bool enabled = options_.techniques.contains(s, t);
  const std::optional<Isolation>& isolate = options_.isolate;
  const bool isolated = isolate && isolate->technique() == Technique{s, t};
  return TechniqueUse{enabled, isolate ? isolated && (enabled || isolate->unweighted) : enabled,
                      isolated && isolate->unweighted, s + t - 1 <= pyramidLength};
}

BidirTracer::TechniqueUse BidirTracer::techniqueUse(Technique x, int pyramidLength) const {
  const bool enabled = options_.techniques.contains(x);
  const std::optional<Isolation>& isolate = options_.isolate;
  const bool isolated = isolate && isolate->technique() == x;
  return TechniqueUse{enabled, isolate ? isolated && (enabled || isolate->unweighted) : enabled,
                      isolated && isolate->unweighted, x.length() <= pyramidLength};
}

// Out of line, one function per instance: inlined into the sample loop, its four instances cost
// 1.3 % more instructions per sample (callgrind; the loop's registers spill).
template <bool kRecords, bool kTimed, class ConnectionRng>
[[gnu::noinline]] void BidirTracer::evaluate(int s, int t, const TechniqueUse& use, Vec2 pRaster,
                                             uint64_t connectionKey, Walks& walks, SampleSink& sink,
                                             Counters& counters, ConnectionRng* connectionRng) const {
  TechniqueTally<kTimed> tally(counters, Technique{s, t});
  const SinkDemand& demand = sink.demand();
  // The record the sink receives (kRecords); the image-only instance never fills it.
  TechniqueResult r;
  if constexpr (kRecords) {
    r.s = s;
    r.t = t;
    r.pRaster = pRaster;
    r.inImage = use.inImage;
    r.inPyramid = use.inPyramid;
  }
  float w = 0.f, imageWeight = 0.f;
  auto finishWithout = [&](TechniqueOutcome outcome) {
    if (outcome == TechniqueOutcome::Blocked) tally.blocked();
    else tally.zero();
    if constexpr (kRecords) {
      if (demand.everyTechnique) {
        r.outcome = outcome;
        r.weight = 0.f;
        r.imageWeight = imageWeight;
        r.inImage = false;
        sink.record(r);
      }
    }
  };

  // Interior connections skip formConnection's dispatch on s, t and the fresh endpoint. Each
  // connection draws its fresh light or lens sample from a stream of its own (connectionStream).
  Connection& c = walks.connection;
  bool formed;
  if (s >= 2 && t >= 2) {
    c.hasSampled = false;  // as formConnection leaves it: no endpoint drawn afresh
    formed = formInteriorConnection(scene_, walks.light, s, walks.camera, t, c);
  } else if constexpr (std::is_same_v<ConnectionRng, Pcg32>) {
    Pcg32 rng = connectionStream(connectionKey, s, t);
    formed = formConnection(scene_, camera_, walks.light, s, walks.camera, t, rng, c);
  } else {
    formed = formConnection(scene_, camera_, walks.light, s, walks.camera, t, *connectionRng, c);
  }
  if (!formed) return finishWithout(TechniqueOutcome::Zero);

  // The weight is computed over the enabled set (a disabled technique's share is zero) before the
  // shadow ray, which is traced only when something will use the contribution. With every
  // technique enabled and the result in the image the weight is positive unless the connection
  // edge itself is shorter than --min-connection (mis.h UsableTechniques; otherwise only
  // degenerate densities, an overflow say, give zero), so there the shadow ray goes first and a
  // blocked path skips its weight: in the Cornell box 13-17 % of the connections with a shadow ray
  // are blocked. Either order gives the sink the same results.
  const MisPath path{walks.light.data(), s, walks.camera.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
  const bool shortConnection = s >= 1 && c.edgeLength2 < minConnectionDistance_ * minConnectionDistance_;
  // --medium-sampling equiangular: E(1, t) takes over most of C(1, t)'s paths through a medium
  // vertex, where C(1, t)'s weight is zero: weigh before tracing its shadow ray.
  const bool takenOverByE = equiangular_ && s == 1 && options_.mis.mediumSampling == MediumSampling::Equiangular &&
                            walks.camera[t - 1].type == VertexType::Medium;
  const bool visibilityFirst = !shortConnection && !takenOverByE && (!kRecords || (misEvaluation_ == MisEvaluation::PartialSums &&
                                                                  use.inImage && !options_.checkMis &&
                                                                  !demand.onPath && !demand.everyContribution));
  // Whether the weighed result is used; false leaves it zero (and traces no shadow ray).
  // Variance-aware MIS: the factors where the path lands (a splat's pixel for t = 1), or null.
  const float* factors = nullptr;
  auto weigh = [&] {
    if (varianceAware_)
      factors = varianceAware_->factorsOfLength(varianceAware_->regionOf(t == 1 ? c.pRaster : pRaster), s + t - 1);
    else
      factors = lightPathCountsOfLength(s + t - 1);  // null at --light-paths 1
    if (use.enabled) w = weight<kRecords>(path, c, walks, factors, counters);
    imageWeight = !use.inImage ? 0.f : use.unweightedInImage ? 1.f : w;
    if (!(imageWeight > 0.f) && !use.inPyramid && !demand.everyContribution) {
      w = 0.f;
      return false;
    }
    return true;
  };
  if (!visibilityFirst) {
    const bool used = weigh();
    if constexpr (kRecords) {
      if (demand.onPath) {
        // The inspector shows blocked paths too: what each technique would have made of them.
        tracePath(scene_, camera_, path, walks.traced);
        r.traced = &walks.traced;
        walks.onPath = techniquesOnPath(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(),
                                        mergesOnPath(mergePass_, options_.mergeSite),
                                        varianceAware_ ? factors : nullptr, lightPathCountsOfLength(s + t - 1));
        r.onPath = &walks.onPath;
      }
    }
    if (!used) return finishWithout(TechniqueOutcome::Zero);
  }
  if (needsShadowRay(s)) {
    tally.shadowRay();
    if (scene_.hasMedia()) {
      // The connection edge's transmittance through the media it crosses (the seed's T_r).
      const Spectrum T = transmittance(scene_, c.shadowRay);
      if (isBlack(T)) return finishWithout(TechniqueOutcome::Blocked);
      c.L *= T;
    } else if (!unoccluded(scene_, c.shadowRay)) {
      return finishWithout(TechniqueOutcome::Blocked);
    }
  }
  if (visibilityFirst && !weigh()) return finishWithout(TechniqueOutcome::Zero);
  tally.contributed();

  Spectrum L = c.L;
  // A technique that walks the light subpath had one on a fraction F of the camera samples: each
  // contribution stands for 1 / F of them (light_paths.h).
  if (lightPathScale_ != 1.f && lightWalkNeeded(s, t)) L *= lightPathScale_;
  if (options_.injectBias && options_.injectBias->technique() == Technique{s, t})
    L *= options_.injectBias->factor;  // a deliberately wrong technique (BiasInjection)
  // The one check of a contribution: NaN, Inf and negative values are dropped one technique at a
  // time, at the door, before any output sees them.
  if (!isValidContribution(L)) return tally.discard(L, sink.id());
  if (t == 1) pRaster = c.pRaster;
  if constexpr (kRecords) {
    r.outcome = TechniqueOutcome::Contributed;
    r.unweighted = L;
    r.weight = w;
    r.imageWeight = imageWeight;
    r.pRaster = pRaster;
    if (demand.sampleable)
      r.sampleableBy = merges_ ? sampleableWithMerges(path, TechniqueKind::Connection, options_.mergeSite)
                       : equiangular_ && equiangularCanSampleAt(scene_, path)
                           ? sampleableTechniques(path) | equiangularSlotBit(s + t - 1)
                           : sampleableTechniques(path);
    if (demand.densityRatios) {
      walks.densityRatios.resize(static_cast<size_t>(s + t));
      techniqueDensityRatios(scene_, camera_, path, walks.densityRatios.data());
      r.densityRatios = walks.densityRatios.data();
    }
    if (demand.lightWalkWeight)
      r.lightWalkWeight = lightWalkWeight(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(), factors);
    if (demand.balanceWeights) {
      walks.balanceWeights.resize(static_cast<size_t>(s + t));
      balanceWeights(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(), factors,
                     walks.balanceWeights.data());
      r.balanceWeights = walks.balanceWeights.data();
      r.omittedFactor = (s >= 1 ? lightVertex(path, s - 1).omittedFactor : 1.f) *
                         (t >= 2 ? cameraVertex(path, t - 1).omittedFactor : 1.f);
    }
    sink.record(r);
  }
  if (!use.inImage) return;
  const Spectrum contribution = L * imageWeight;
  if (!isBlack(contribution) && !sink.toImage(t, pRaster, contribution)) tally.discard(contribution, sink.id());
}

template <bool kRecords>
[[gnu::always_inline]] inline void BidirTracer::evaluate(bool timed, int s, int t, const TechniqueUse& use,
                                                         Vec2 pRaster, uint64_t connectionKey, Walks& walks,
                                                         SampleSink& sink, Counters& counters) const {
  if (timed) {
    evaluate<kRecords, true>(s, t, use, pRaster, connectionKey, walks, sink, counters);
  } else {
    evaluate<kRecords, false>(s, t, use, pRaster, connectionKey, walks, sink, counters);
  }
}

template <class Rng>
int BidirTracer::walkCamera(Vec2 pRaster, Vec2 uLens, int vertices, Rng& rng, Walks& walks, Counters& counters) const {
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, rng,
                                       WalkOptions{vertices, options_.russianRoulette, cameraMedium_, equiangular_},
                                       walks.camera, counters);
  if (misEvaluation_ == MisEvaluation::PartialSums) {
    if (mergePass_)
      accumulateCameraSums(walks.camera, misPower_, lightTracingRatio(), walks.cameraSums, mergeTerms(*mergePass_));
    else
      accumulateCameraSums(walks.camera, misPower_, lightTracingRatio(), walks.cameraSums, {}, countsInWeights());
  }
  return nt;
}

template <class Rng>
int BidirTracer::walkLight(int vertices, Rng& rng, Walks& walks, Counters& counters) const {
  if (vertices <= 0) return 0;
  const int ns = generateLightSubpath(scene_, rng, WalkOptions{vertices, options_.russianRoulette}, walks.light, counters);
  if (ns > 0 && misEvaluation_ == MisEvaluation::PartialSums)
    accumulateLightSums(walks.light, misPower_, walks.lightSums, {}, countsInWeights());
  return ns;
}

int BidirTracer::traceLightSubpath(Pcg32& lightRng, std::vector<PathVertex>& out, Counters& counters) const {
  // The walk alone: a merge pass accumulates its paths' sums once the pass's radius is known
  // (prepareMergePass).
  thread_local LightSubpath path;
  const int ns = lightVerticesNeeded_ > 0 ? generateLightSubpath(scene_, lightRng,
                                                                 WalkOptions{lightVerticesNeeded_, options_.russianRoulette},
                                                                 path, counters)
                                          : 0;
  out.insert(out.end(), path.data(), path.data() + ns);
  return ns;
}

MergeTerms BidirTracer::mergeTerms(const MergePass& pass) const {
  return MergeTerms{connectionsInSums_, true, pass.eta(), pass.nonCaustic};
}

void BidirTracer::prepareMergePass(MergePass& pass) const {
  resizeWithRoom(pass.misSum, pass.vertexCount());
  resizeWithRoom(pass.misShortestEdge2, pass.vertexCount());
  if (misEvaluation_ != MisEvaluation::PartialSums) return;
  const MergeTerms terms = mergeTerms(pass);
  tbb::parallel_for(size_t{0}, pass.pixelPathStart.size(), [&](size_t p) {
    const uint32_t start = pass.pixelPathStart[p], count = pass.pixelPathCount[p];
    if (count > 0)
      accumulateLightSums(pass.pixelPath[p], static_cast<int>(count), misPower_, &pass.misSum[start],
                          &pass.misShortestEdge2[start], terms);
  });
  tbb::parallel_for(size_t{0}, pass.records.size(), [&](size_t j) {
    MergeRecord& record = pass.records[j];
    const uint32_t start = record.vertex - static_cast<uint32_t>(record.s - 1);
    const PathVertex* path = pass.mergeableVertex[pass.grid.pointOfSlot(static_cast<uint32_t>(j))] - (record.s - 1);
    record.mis = mergeLightTerms(scene_, path, record.s, &pass.misSum[start],
                                 &pass.misShortestEdge2[start], misPower_, terms);
  });
}

template <class Rng>
void BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Rng& cameraRng, Rng& lightRng, SampleSink& sink,
                         Counters& counters) const {
  // The connections' key is drawn first, so that how long the walks below are allowed to grow
  // changes no connection's random numbers.
  const uint64_t keyHigh = cameraRng.nextU32();  // two statements: operand order is unspecified
  const uint64_t connectionKey = keyHigh << 32 | cameraRng.nextU32();

  thread_local Walks walks;
  const bool timed = timing_ && connectionKey % kTimedSampleStride == 0;
  if (timed) ++counters.timedSamples;
  const SinkDemand& demand = sink.demand();
  const int pyramidLength = demand.pyramid ? options_.pyramidLength : 0;
  if (options_.connect == ConnectStrategy::Endpoints) {
    sampleEndpoints(pRaster, uLens, connectionKey, timed, pyramidLength, walks, sink, counters);
    return;
  }

  // Each walk stops at the longest prefix any technique in use needs (light tracing needs no
  // camera walk at all).
  const uint64_t raysBefore = counters.rays;
  const uint64_t walkStart = timed ? ticks() : 0;
  const int nt = walkCamera(pRaster, uLens, cameraVerticesNeeded_, cameraRng, walks, counters);
  const uint64_t cameraRays = counters.rays, cameraEnd = timed ? ticks() : 0;
  // With merges the pass already walked this pixel's light subpath (from the same stream) and
  // stored it: the connections take it from there.
  // --light-paths F: the light walk (and every technique that needs it) on a fraction F of the
  // camera samples (light_paths.h).
  const int ns = mergePass_                                                ? storedLightSubpath(sink.id(), walks)
                 : walksLightSubpath(connectionKey, options_.lightPaths) ? walkLight(lightVerticesNeeded_, lightRng, walks, counters)
                                                                          : 0;
  counters.cameraWalk.rays += cameraRays - raysBefore;
  counters.lightWalk.rays += counters.rays - cameraRays;
  if (timed) {
    counters.cameraWalk.nanoseconds += elapsedNanoseconds(walkStart, cameraEnd);
    counters.lightWalk.nanoseconds += elapsedNanoseconds(cameraEnd, ticks());
  }
  sink.beginSample({walks.camera.data(), static_cast<size_t>(nt)}, {walks.light.data(), static_cast<size_t>(ns)});

  // The image-only route: every technique enabled and used by the image alone (no isolation),
  // hence TechniqueUse's defaults.
  const bool imageOnly = imageOnlyPathActive() && !demand.records();
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= std::max(ns, 1); ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > options_.maxLength) continue;
      if (s > ns && lightWalkNeeded(s, t)) continue;
      const bool recorded = !imageOnly || k <= pyramidLength;
      TechniqueUse use;
      if (recorded) {
        use = techniqueUse(s, t, pyramidLength);
        if (!use.used()) continue;
      }
      if (s == 0 && walks.camera[t - 1].light < 0 && !timed && !demand.everyTechnique) {
        // The camera subpath's own vertex is no emitter: formConnection would refuse (s = 0), so
        // the try is tallied as zero without evaluate's machinery (one try in seven in the
        // Cornell box).
        TechniqueTally<false>(counters, Technique{s, t}).zero();
        continue;
      }
      if (recorded) {
        evaluate<true>(timed, s, t, use, pRaster, connectionKey, walks, sink, counters);
      } else {
        evaluate<false>(timed, s, t, use, pRaster, connectionKey, walks, sink, counters);
      }
    }
  if (equiangular_) evaluateEquiangular(pRaster, connectionKey, pyramidLength, walks, sink, counters);
  if (mergePass_) evaluateMerges(timed, nt, pRaster, pyramidLength, walks, sink, counters);
}

void BidirTracer::setLightPaths(float lightPaths) {
  options_.lightPaths = lightPaths;
  if (lightPaths < 1.f) {
    lightPathCounts_ = lightPathCounts(options_.maxLength, lightPaths);
    lightPathScale_ = 1.f / lightPaths;
  } else {
    lightPathCounts_.clear();
    lightPathScale_ = 1.f;
  }
}

void BidirTracer::evaluateEquiangular(Vec2 pRaster, uint64_t connectionKey, int pyramidLength, Walks& walks,
                                      SampleSink& sink, Counters& counters) const {
  const CameraSubpath& camera = walks.camera;
  const SinkDemand& demand = sink.demand();
  // E(1, t) needs the ray z(t-2) shot, not z(t-1): t up to one past the recorded rays.
  const int last = std::min(camera.rayCount + 1, options_.maxLength);
  std::vector<PathVertex>& prefix = walks.equiangularCamera;
  if (prefix.size() < static_cast<size_t>(last)) prefix.resize(static_cast<size_t>(last));
  Connection& c = walks.connection;
  for (int t = 2; t <= last; ++t) {
    // E's path: the light sample, the camera prefix z(0) .. z(t-2), then x (prefix holds the
    // vertices before z(t-2) from the previous t already: one copy per t).
    prefix[static_cast<size_t>(t - 2)] = camera[t - 2];
    const Technique e = Technique::equiangular(t);
    const TechniqueUse use = techniqueUse(e, pyramidLength);
    if (!use.used()) continue;
    TechniqueTally<false> tally(counters, e);
    const bool records = use.inPyramid || demand.records();
    TechniqueResult r;
    r.s = 1, r.t = t, r.kind = TechniqueKind::Equiangular;
    r.pRaster = pRaster, r.inImage = use.inImage, r.inPyramid = use.inPyramid;
    float w = 0.f, imageWeight = 0.f;
    auto finishWithout = [&](TechniqueOutcome outcome) {
      if (outcome == TechniqueOutcome::Blocked) tally.blocked();
      else tally.zero();
      if (demand.everyTechnique) {
        r.outcome = outcome, r.weight = 0.f, r.imageWeight = imageWeight, r.inImage = false;
        sink.record(r);
      }
    };
    Pcg32 rng = equiangularStream(connectionKey, t);
    PathVertex& x = prefix[static_cast<size_t>(t - 1)];
    if (!formEquiangularConnection(scene_, camera, t, rng, x, c, counters)) {
      finishWithout(TechniqueOutcome::Zero);
      continue;
    }
    const MisPath path{&c.sampled, 1, prefix.data(), t, &c.sampled, &c.pdfs};
    const float* factors = varianceAware_ ? varianceAware_->factorsOfLength(varianceAware_->regionOf(pRaster), t)
                                          : lightPathCountsOfLength(t);
    if (use.enabled)
      w = equiangularMisWeight(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(), factors);
    imageWeight = !use.inImage ? 0.f : use.unweightedInImage ? 1.f : w;
    if (demand.onPath) {
      tracePath(scene_, camera_, path, walks.traced);
      r.traced = &walks.traced;
      walks.onPath = techniquesOnPath(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(),
                                      std::nullopt, varianceAware_ ? factors : nullptr, lightPathCountsOfLength(t));
      r.onPath = &walks.onPath;
    }
    if (!(imageWeight > 0.f) && !use.inPyramid && !demand.everyContribution) {
      finishWithout(TechniqueOutcome::Zero);
      continue;
    }
    tally.shadowRay();
    const Spectrum T = transmittance(scene_, c.shadowRay);
    if (isBlack(T)) {
      finishWithout(TechniqueOutcome::Blocked);
      continue;
    }
    tally.contributed();
    Spectrum L = c.L * T;
    if (options_.injectBias && options_.injectBias->technique() == e) L *= options_.injectBias->factor;
    if (!isValidContribution(L)) {
      tally.discard(L, sink.id());
      continue;
    }
    if (records) {
      r.outcome = TechniqueOutcome::Contributed;
      r.unweighted = L, r.weight = w, r.imageWeight = imageWeight;
      // The connections able to sample E's path, and E itself (its slot 2t).
      if (demand.sampleable) r.sampleableBy = sampleableTechniques(path) | equiangularSlotBit(t);
      if (demand.lightWalkWeight)
        r.lightWalkWeight =
            lightWalkWeight(scene_, camera_, path, options_.techniques, options_.mis, lightTracingRatio(), factors, true);
      sink.record(r);
    }
    if (!use.inImage) continue;
    const Spectrum contribution = L * imageWeight;
    if (!isBlack(contribution) && !sink.toImage(t, pRaster, contribution)) tally.discard(contribution, sink.id());
  }
}

template void BidirTracer::sample(Vec2, Vec2, Pcg32&, Pcg32&, SampleSink&, Counters&) const;
template void BidirTracer::sample(Vec2, Vec2, PrimarySampleStream&, PrimarySampleStream&, SampleSink&, Counters&) const;

namespace {
// sampleTechnique's sink: the one technique's weighted contribution and where it lands, its subpaths
// and record passed on to the caller's sink when it asks for them (`forward`, with its demand).
class TechniqueSampleSink final : public SampleSink {
 public:
  explicit TechniqueSampleSink(SampleSink* forward)
      : SampleSink(forward ? forward->demand() : SinkDemand{}, forward ? forward->id() : SampleId{}),
        forward_(forward) {}
  Spectrum splatted{0.f};
  Vec2 splatAt{0.f};
  void record(const TechniqueResult& result) override {
    if (forward_) forward_->record(result);
  }

 protected:
  bool splat(Vec2 pRaster, const Spectrum& v) override {
    splatted = v, splatAt = pRaster;
    return true;
  }

 private:
  SampleSink* forward_;
};
}  // namespace

BidirTracer::TechniqueSample BidirTracer::sampleTechnique(int s, int t, Vec2 pRaster, Vec2 uLens,
                                                          PrimarySampleStream& cameraRng, PrimarySampleStream& lightRng,
                                                          PrimarySampleStream& connectionRng, Counters& counters,
                                                          SampleSink* records) const {
  // As sampleEndpoints' technique, on the primary sample's streams: the camera walk, then the
  // light walk, then the one evaluation of the technique (evaluate), whose fresh endpoint (s = 1,
  // t = 1) comes from the connection stream; each from a stream of its own so that a small step on
  // one moves the others little.
  thread_local Walks walks;
  const int nt = walkCamera(pRaster, uLens, t, cameraRng, walks, counters);
  const int ns = nt < t || !lightWalkNeeded(s, t) ? 0 : walkLight(s, lightRng, walks, counters);
  if (records) records->beginSample({walks.camera.data(), static_cast<size_t>(nt)}, {walks.light.data(), static_cast<size_t>(ns)});
  if (nt < t || (lightWalkNeeded(s, t) && ns < s)) {
    TechniqueTally<false>(counters, Technique{s, t}).zero();  // a walk ended early
    return {Spectrum(0.f), pRaster};
  }
  const bool enabled = options_.techniques.contains(s, t);
  TechniqueSampleSink sink(records);
  evaluate<true, false>(s, t, TechniqueUse{enabled, enabled, false, false}, pRaster, 0, walks, sink, counters,
                        &connectionRng);
  if (t == 1) return {sink.splatted, sink.splatAt};
  return {sink.cameraEstimate(), pRaster};
}

int BidirTracer::storedLightSubpath(const SampleId& id, Walks& walks) const {
  const MergePass& pass = *mergePass_;
  const size_t pixel = static_cast<size_t>(id.y) * static_cast<size_t>(pass.width) + static_cast<size_t>(id.x);
  if (pixel >= pass.pixelPathCount.size()) return 0;
  const int n = static_cast<int>(pass.pixelPathCount[pixel]);
  LightSubpath& path = walks.light;
  path.setCapacity(std::max(n, 1));
  path.count = n;
  const PathVertex* stored = pass.pixelPath[pixel];
  for (int i = 0; i < n; ++i) {
    const PathVertex& v = path[i] = stored[i];
    // The BSDF the walk built beside each surface vertex, built again from the same inputs.
    if (v.type == VertexType::Surface)
      path.bsdfs[static_cast<size_t>(i)] = scene_.bsdf(v.material, ShadingInputs{v.uv, v.uv1, v.color}, v.ns, v.ng);
  }
  if (n > 0 && misEvaluation_ == MisEvaluation::PartialSums) {
    // The pass accumulated this path's sums (MergePass::misSum): sum[0 .. n-1] and the shortest
    // edges; sum[n], the whole path's, no connection reads.
    const size_t start = pass.pixelPathStart[pixel], count = static_cast<size_t>(n);
    SubpathMisSums& sums = walks.lightSums;
    sums.sum.assign(pass.misSum.begin() + static_cast<std::ptrdiff_t>(start),
                    pass.misSum.begin() + static_cast<std::ptrdiff_t>(start + count));
    sums.sum.push_back(0.0);
    sums.shortestEdge2.assign(pass.misShortestEdge2.begin() + static_cast<std::ptrdiff_t>(start),
                              pass.misShortestEdge2.begin() + static_cast<std::ptrdiff_t>(start + count));
  }
  return n;
}

void BidirTracer::evaluateMerges(bool timed, int nt, Vec2 pRaster, int pyramidLength, Walks& walks,
                                 SampleSink& sink, Counters& counters) const {
  if (!timed) return evaluateMerges<false>(nt, pRaster, pyramidLength, walks, sink, counters);
  // The merges' own time goes to their techniques (TechniqueTally); what is left of the whole is
  // the range searches'.
  auto techniqueTime = [&] {
    uint64_t ns = 0;
    for (const TechniqueCounters& t : counters.techniques) ns += t.nanoseconds;
    return ns;
  };
  const uint64_t mergesBefore = techniqueTime(), start = ticks();
  evaluateMerges<true>(nt, pRaster, pyramidLength, walks, sink, counters);
  const uint64_t total = elapsedNanoseconds(start, ticks()), merges = techniqueTime() - mergesBefore;
  counters.mergeSearch.nanoseconds += total > merges ? total - merges : 0;
}

template <bool kTimed>
void BidirTracer::evaluateMerges(int nt, Vec2 pRaster, int pyramidLength, Walks& walks, SampleSink& sink,
                                 Counters& counters) const {
  // Vertex merging (Georgiev et al. 2012 eq. 11): camera vertex z(t-1) and light vertex y(s-1)
  // within r make one vertex; the path's contribution over its density is
  //   beta_camera(z) f_z(toward z(t-2), toward y(s-2)) beta_light(y) / (pi r^2 N),
  // the camera vertex's BSDF standing for the merged vertex's (each beta stops short of its own
  // vertex's cosine, which the density estimate's area measure absorbs).
  const MergePass& pass = *mergePass_;
  const MergeMis mis{pass.eta(), options_.mergeSite == MergeSite::FirstNonSpecular, pass.nonCaustic};
  const MergeTerms terms = mergeTerms(pass);
  const float normalisation = static_cast<float>(pass.normalisation());
  const SinkDemand& demand = sink.demand();
  const std::optional<Isolation>& isolate = options_.isolate;
  const bool firstNonSpecularOnly = options_.mergeSite == MergeSite::FirstNonSpecular;
  // Variance-aware MIS: the camera sample's region, where every merge of it lands.
  const int factorRegion = varianceAware_ ? varianceAware_->regionOf(pRaster) : -1;
  for (int t = 2; t <= nt; ++t) {
    // Progressive photon mapping: nothing beyond the first vertex that is not a delta scatter.
    if (firstNonSpecularOnly && t >= 3 && !walks.camera[t - 2].isDelta) break;
    const PathVertex& z = walks.camera[t - 1];
    if (z.type != VertexType::Surface || z.isDelta) continue;
    const Bsdf& bsdf = walks.camera.bsdf(t - 1);
    // z's half of every merge weight at z, once for all the light vertices it finds, formed at the
    // first: most camera vertices find none where the pass keeps few (MergePass::nonCaustic).
    const bool partialSums = misEvaluation_ == MisEvaluation::PartialSums;
    std::optional<MergeCameraTerms> cameraTerms;
    pass.grid.querySlots(z.p, [&](uint32_t slot) {
      const MergeRecord& record = pass.records[slot];
      const int s = record.s;
      const Technique x = Technique::merge(s, t);
      if (x.length() > options_.maxLength) return;
      const bool enabled = options_.techniques.contains(x);
      // As techniqueUse: with an isolation only the isolated technique reaches the image, weighted
      // (if enabled) or unweighted.
      const bool isolated = isolate && isolate->technique() == x;
      const bool inImage = isolate ? isolated && (enabled || isolate->unweighted) : enabled;
      const bool shownUnweighted = isolated && isolate->unweighted;
      const bool inPyramid = x.length() <= pyramidLength;
      if (!inImage && !inPyramid) return;
      TechniqueTally<kTimed> tally(counters, x);
      const BsdfEval f = bsdf.eval(z.wo, record.wo, TransportMode::Radiance);
      Spectrum L = z.beta * f.f * record.beta * normalisation;
      if (options_.injectBias && options_.injectBias->technique() == x) L *= options_.injectBias->factor;
      if (isBlack(L)) return tally.zero();
      // The merged path's two densities at z's BSDF (mergedPathDensities): toward y(s-2) and z(t-2).
      const MergePdfs pdfs{f.pdfFwdW, f.pdfRevW};
      const uint32_t start = record.vertex - static_cast<uint32_t>(s - 1);
      float w = 0.f;
      // Variance-aware MIS: the factors of the merged path's length there.
      const float* factors = varianceAware_ ? varianceAware_->factorsOfLength(factorRegion, x.length()) : nullptr;
      if (enabled) {
        std::optional<float> fast;
        if (partialSums) {
          if (!cameraTerms)
            cameraTerms = mergeCameraTerms(walks.camera, t, walks.cameraSums, misPower_, lightTracingRatio(), terms);
          fast = mergeWeightFromTerms(record.mis, *cameraTerms, pdfs, misPower_, terms, minConnectionDistance_);
        }
        w = fast ? *fast
                 : mergeWeight(&pass.vertex(start), s, walks.camera.data(), t, pdfs, options_.techniques,
                               options_.mis, lightTracingRatio(), minConnectionDistance_, mis, factors);
      }
      tally.contributed();
      if (!isValidContribution(L)) return tally.discard(L, sink.id());
      if (demand.records() || inPyramid) {
        TechniqueResult r;
        r.s = s;
        r.t = t;
        r.kind = TechniqueKind::Merge;
        r.outcome = TechniqueOutcome::Contributed;
        r.unweighted = L;
        r.weight = w;
        r.imageWeight = !inImage ? 0.f : shownUnweighted ? 1.f : w;
        r.pRaster = pRaster;
        r.inImage = inImage;
        r.inPyramid = inPyramid;
        // The merged path's vertices as connection C(s, t - 1) holds them (merge_sampleable.h).
        if (demand.sampleable) {
          const MisPath path{&pass.vertex(start), s, walks.camera.data(), t - 1, nullptr, nullptr};
          r.sampleableBy = sampleableWithMerges(path, TechniqueKind::Merge, options_.mergeSite);
        }
        if (demand.onPath) inspectMerge(pass, record.vertex, s, t, pdfs, factors, walks, r);
        sink.record(r);
      }
      const float imageWeight = shownUnweighted ? 1.f : w;
      if (!inImage || !(imageWeight > 0.f)) return;
      if (!sink.toImage(t, pRaster, L * imageWeight)) tally.discard(L * imageWeight, sink.id());
    }, [&](uint32_t slot) { __builtin_prefetch(&pass.records[slot]); });
  }
}

void BidirTracer::inspectMerge(const MergePass& pass, uint32_t lightVertex, int s, int t, const MergePdfs& pdfs,
                               const float* factors, Walks& walks, TechniqueResult& r) const {
  // Listed on the path the weight was computed on (mergedPathDensities), so that the inspector's
  // densities and weights are the render's.
  const uint32_t start = lightVertex - static_cast<uint32_t>(s - 1);
  const PathVertex& z = walks.camera[t - 1];
  const PathVertex* light = &pass.vertex(start);
  const MisPath path{light, s, walks.camera.data(), t - 1, nullptr, nullptr};
  r.merged = MergedVertices{light[s - 1].p, z.p, z.ng, pass.radius};
  MergedPath merged;
  mergedPathDensities(light, s, walks.camera.data(), t, pdfs, merged.densities, merged.surface);
  tracePath(scene_, camera_, path, walks.traced, &merged.densities);
  r.traced = &walks.traced;
  walks.onPath = techniquesOnMergedPath(scene_, path, merged, options_.techniques, options_.mis, lightTracingRatio(),
                                        *mergesOnPath(&pass, options_.mergeSite), factors);
  r.onPath = &walks.onPath;
}

void BidirTracer::sampleEndpoints(Vec2 pRaster, Vec2 uLens, uint64_t connectionKey, bool timed, int pyramidLength,
                                  Walks& walks, SampleSink& sink, Counters& counters) const {
  // The seed's naive BPT: for each technique a light subpath of exactly s and a camera subpath of
  // exactly t vertices, sampled independently (every camera subpath through the sample's pRaster
  // and uLens), joined at their endpoints only. The weights are functions of the path alone, so
  // they are those of path reuse and still a partition of unity; the partial sums are those of the
  // technique's own subpaths. The walks' rays and time go to the technique's own row.
  sink.beginSample({}, {});
  for (const Technique x : techniquesUpTo(options_.maxLength)) {
    const TechniqueUse use = techniqueUse(x.s, x.t, pyramidLength);
    if (!use.used()) continue;
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
    sink.walked(nt, ns);
    if (nt < x.t || (lightWalkNeeded(x.s, x.t) && ns < x.s)) continue;  // a walk ended early
    evaluate<true>(timed, x.s, x.t, use, pRaster, connectionKey, walks, sink, counters);
  }
}

}  // namespace pathlab
