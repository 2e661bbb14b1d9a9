// Recursive MIS partial sums: accumulated along each walk, patched at the connection.
#include "core/bpt/mis_partial_sums.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

namespace pathlab {

namespace {

constexpr float kNoEdge = std::numeric_limits<float>::infinity();

double ratio(double numerator, double denominator) { return remap0(numerator) / remap0(denominator); }

void accumulateShortestEdges(const PathVertex* path, int count, float* shortestEdge2) {
  shortestEdge2[0] = kNoEdge;
  for (int i = 1; i < count; ++i) shortestEdge2[i] = std::min(shortestEdge2[i - 1], edgeLength2(path[i - 1], path[i]));
}

// A merge's term of the sums: T(eta keep pFromCamera(merged vertex)), a zero density (a delta lobe
// next to the merged vertex) counting one as in the ratios (merge_mis.cpp); `caustic`: the merged
// vertex's predecessor on the light side is a delta vertex (mergeKeep).
[[gnu::always_inline]] inline double mergeTerm(const MisPower& power, const MergeTerms& m, double pFromCamera,
                                               bool caustic) {
  return power(m.eta * mergeKeep(m.nonCaustic, caustic) * remap0(pFromCamera));
}

// sum[0 .. count] of a light subpath (sum[count] when withLast).
template <bool kMerges>
void lightSums(const PathVertex* path, int count, const MisPower& power, const MergeTerms& m, double* sum,
               bool withLast, double* steps = nullptr, double* counts = nullptr) {
  double left = 0.0;
  sum[0] = left;
  const int last = withLast ? count : count - 1;
  for (int i = 0; i < last; ++i) {
    const PathVertex& v = path[i];
    // Technique s' = i connects x(i-1) and x(i); s' = 0 needs x0 on an area light; s' = 1 a
    // next-event density above zero (mis.h techniquePossible; a light subpath's x0 has pdfFwdA > 0,
    // so pdfNeeA is zero only where a light BVH refuses its light for x1).
    const bool usable = i == 0   ? canBeHitAsOrigin(v) && !v.isDelta
                        : i == 1 ? !path[0].isDelta && !v.isDelta && path[0].pdfNeeA != 0.f
                                 : !path[i - 1].isDelta && !v.isDelta;
    // r_0 = p_0 / p_1 with x0's next-event density; r_1 = p_1 / p_2 then carries the change of
    // x0's density from that to the light subpath's (mis.h ratioToCamera). These sums serve
    // paths of three or more vertices only (sum[1] from s = 3 on), where that applies.
    const double r = i == 0   ? ratio(v.pdfRevA, v.pdfNeeA)
                     : i == 1 ? ratio(v.pdfRevA, v.pdfFwdA) * ratio(path[0].pdfNeeA, path[0].pdfFwdA)
                              : ratio(v.pdfRevA, v.pdfFwdA);
    double w = usable ? 1.0 : 0.0;
    // Merge M(i, .) merges x(i-1) (i >= 2: not the light's origin).
    if constexpr (kMerges) {
      w *= m.connections;
      if (m.merges && i >= 2 && mergeableVertex(path[i - 1]))
        w += mergeTerm(power, m, path[i - 1].pdfRevA, path[i - 2].isDelta);
    }
    const double step = power(r);
    left = step * (w + left);
    sum[i + 1] = left;
    if (steps) steps[i] = step, counts[i] = w;
  }
}

}  // namespace

void accumulateLightSums(const Subpath& path, const MisPower& power, SubpathMisSums& sums, const MergeTerms& merges,
                         bool steps) {
  sums.sum.resize(static_cast<size_t>(path.count) + 1);
  if (steps) {
    sums.step.resize(static_cast<size_t>(path.count));
    sums.count.resize(static_cast<size_t>(path.count));
    lightSums<false>(path.data(), path.count, power, merges, sums.sum.data(), true, sums.step.data(), sums.count.data());
  } else if (merges.merges || merges.connections != 1.0) {
    lightSums<true>(path.data(), path.count, power, merges, sums.sum.data(), true);
  } else {
    lightSums<false>(path.data(), path.count, power, merges, sums.sum.data(), true);
  }
  sums.shortestEdge2.resize(static_cast<size_t>(std::max(path.count, 1)));
  accumulateShortestEdges(path.data(), path.count, sums.shortestEdge2.data());
}

void accumulateLightSums(const PathVertex* path, int count, const MisPower& power, double* sum, float* shortestEdge2,
                         const MergeTerms& merges) {
  if (count <= 0) return;
  lightSums<true>(path, count, power, merges, sum, false);
  accumulateShortestEdges(path, count, shortestEdge2);
}

namespace {

template <bool kMerges>
void cameraSums(const Subpath& path, const MisPower& power, float lightTracingRatio, const MergeTerms& m,
                SubpathMisSums& sums, bool steps = false) {
  sums.sum.resize(static_cast<size_t>(std::max(path.count, 1)) + 1);
  // No technique has t' = 0: the prefixes of zero and one camera vertex have nothing to sum.
  double right = 0.0;
  sums.sum[0] = sums.sum[1] = right;
  const double lightTracingCount = power(lightTracingRatio);
  for (int j = 1; j < path.count; ++j) {
    const PathVertex& v = path[j];
    // Technique t' = j connects y(j) and y(j-1).
    const bool usable = !v.isDelta && !path[j - 1].isDelta;
    const double count = j == 1 ? lightTracingCount : 1.0;
    double w = usable ? count : 0.0;
    // Its merge merges y(j), sampled by the camera walk (pdfFwdA). Its predecessor on the light
    // side is y(j+1): every technique that reads this sum has it on its camera prefix.
    if constexpr (kMerges) {
      w *= m.connections;
      if (m.merges && mergeableVertex(v))
        w += mergeTerm(power, m, v.pdfFwdA, j + 1 < path.count && path[j + 1].isDelta);
    }
    const double step = power(ratio(v.pdfRevA, v.pdfFwdA));
    right = step * (w + right);
    sums.sum[static_cast<size_t>(j) + 1] = right;
    if (steps) sums.step[static_cast<size_t>(j)] = step, sums.count[static_cast<size_t>(j)] = w;
  }
  sums.shortestEdge2.resize(static_cast<size_t>(std::max(path.count, 1)));
  accumulateShortestEdges(path.data(), path.count, sums.shortestEdge2.data());
}

}  // namespace

void accumulateCameraSums(const Subpath& path, const MisPower& power, float lightTracingRatio, SubpathMisSums& sums,
                          const MergeTerms& merges, bool steps) {
  if (steps) {
    sums.step.assign(static_cast<size_t>(std::max(path.count, 1)), 0.0);
    sums.count.assign(static_cast<size_t>(std::max(path.count, 1)), 0.0);
    cameraSums<false>(path, power, lightTracingRatio, merges, sums, true);
  } else if (merges.merges || merges.connections != 1.0)
    cameraSums<true>(path, power, lightTracingRatio, merges, sums);
  else
    cameraSums<false>(path, power, lightTracingRatio, merges, sums);
}

namespace {

// An edge of the path shorter than minConnectionDistance: the prefixes' shortest edges (the fresh
// endpoint of s = 1 or t = 1 stands alone on its side) and the connection's own, connection2
// (infinite when there is none: s = 0). lightShortest[i] / cameraShortest[j]: the shortest edge of
// the prefix of i + 1 / j + 1 vertices.
[[gnu::always_inline]] inline bool hasShortEdge(int s, int t, float connection2, const float* lightShortest,
                                                const float* cameraShortest, float minConnectionDistance) {
  const float minDistance2 = minConnectionDistance * minConnectionDistance;
  if (!(minDistance2 > 0.f)) return false;
  float shortest = kNoEdge;
  if (s >= 2) shortest = std::min(shortest, lightShortest[s - 1]);
  if (t >= 2) shortest = std::min(shortest, cameraShortest[t - 1]);
  shortest = std::min(shortest, connection2);
  return shortest < minDistance2;
}

// The weight from the sums once the connection's densities are known: every entry point below.
// Inline into each, so that the interior one (s, t >= 2 known) loses the branches of s <= 1.
// lightSum / cameraSum: SubpathMisSums::sum of each side. kMerges: the sums and the weight count
// the merges (MergeTerms). A merge's weight has its own entry point (mergeWeightFromTerms).
// kFactors: variance-aware MIS, each technique's count times factors[s'] (connections only), the
// sums beyond the connection's two patched steps summed again from the walks' steps (SubpathMisSums).
template <bool kMerges, bool kFactors = false>
[[gnu::always_inline]] inline std::optional<float> weightFromSums(const Scene& scene, const MisPath& path,
                                                                  const ConnectionEnds& e, const ConnectionDensities& c,
                                                                  const double* lightSum, const double* cameraSum,
                                                                  const MisPower& power, float lightTracingRatio,
                                                                  const MergeTerms& m,
                                                                  const SubpathMisSums* lightAll = nullptr,
                                                                  const SubpathMisSums* cameraAll = nullptr,
                                                                  const float* factors = nullptr) {
  static_assert(!(kMerges && kFactors), "variance-aware weights with merges are the explicit ones");
  const int s = path.s, t = path.t;
  // The factor of technique s' of this path's length (one without factors).
  auto factor = [&](int sp) -> double {
    if constexpr (kFactors) return static_cast<double>(factors[sp]);
    else return 1.0;
  };
  const PathVertex& pt = *e.pt;
  // x0's density under technique s' = 1 over its density as a light subpath's origin, for paths
  // of three or more vertices (mis.h PathDensities::x0Nee): what moving between s' = 1 and 2
  // multiplies the ratio by. One when the scene chooses lights by power alone.
  const int n = s + t;
  double neeOverOrigin = 1.0;
  double x0FromLight = c.ptFromLight;  // s = 0: x0 = pt's density as the light side samples it
  bool neeRefused = false;             // s = 0: the BVH cannot choose x0's light for x1
  if (n >= 3 && scene.lights().neeByContext()) {
    if (s >= 1) {
      const PathVertex& x0 = lightVertex(path, 0);
      neeOverOrigin = ratio(x0.pdfNeeA, x0.pdfFwdA);
    } else {
      x0FromLight = pdfNeeOrigin(scene, pt, *e.ptMinus);
      neeOverOrigin = ratio(x0FromLight, c.ptFromLight);
      neeRefused = x0FromLight == 0.0;
    }
  }
  // The connections' count (one, or zero when none is enabled) and the merge of x(s'-1) of
  // technique s' (s' >= 2: x0 is never merged) with its camera-side density.
  const double connections = kMerges ? m.connections : 1.0;
  // `caustic`: x(s'-2), the merged vertex's predecessor on the light side, is a delta vertex.
  auto merge = [&](int sp, const PathVertex& merged, double pFromCamera, bool caustic) {
    if constexpr (!kMerges) return 0.0;
    return m.merges && sp >= 2 && mergeableVertex(merged) ? mergeTerm(power, m, pFromCamera, caustic) : 0.0;
  };
  // Light side: left(s) = T(r_{s-1}) (w(s-1) + T(r_{s-2}) (w(s-2) + left(s-2))). qs and pt count
  // as non-delta (connect() formed the path through them; a merge's qs is its merged vertex).
  double left = 0.0;
  if (e.qs) {
    double beyond = 0.0;
    if (e.qsMinus) {
      // s = 3: the term is technique s' = 1's, which needs x0's next-event density.
      const bool usable = s == 2 ? canBeHitAsOrigin(*e.qsMinus) && !e.qsMinus->isDelta
                                 : !path.lightPath[s - 3].isDelta && !e.qsMinus->isDelta &&
                                       (s != 3 || path.lightPath[0].pdfNeeA != 0.f);
      // s = 2: qsMinus is x0 (r_0, with its next-event density); s = 3: x1 (r_1).
      const double r = s == 2   ? ratio(c.qsMinusFromCamera, e.qsMinus->pdfNeeA)
                       : s == 3 ? ratio(c.qsMinusFromCamera, e.qsMinus->pdfFwdA) * neeOverOrigin
                                : ratio(c.qsMinusFromCamera, e.qsMinus->pdfFwdA);
      double w = usable ? connections : 0.0;
      if constexpr (kMerges)
        if (s >= 4) w += merge(s - 2, path.lightPath[s - 3], path.lightPath[s - 3].pdfRevA, path.lightPath[s - 4].isDelta);
      if constexpr (kFactors) {
        // left(s - 2) with the factors: technique s' = i's count enters at the light vertex x_i.
        double sum = 0.0;
        for (int i = 0; i < s - 2; ++i) sum = lightAll->step[static_cast<size_t>(i)] * (factor(i) * lightAll->count[static_cast<size_t>(i)] + sum);
        beyond = power(r) * (factor(s - 2) * w + sum);
      } else {
        beyond = power(r) * (w + lightSum[s - 2]);
      }
    }
    // s = 2: the term is technique s' = 1's.
    const bool usable = s == 1 ? canBeHitAsOrigin(*e.qs) : !e.qsMinus->isDelta && (s != 2 || e.qsMinus->pdfNeeA != 0.f);
    // s = 1: qs is x0, sampled by next-event estimation unless it meets the lens (t = 1);
    // s = 2: qs is x1 (r_1).
    const double r = s == 1   ? ratio(c.qsFromCamera, n >= 3 ? e.qs->pdfNeeA : e.qs->pdfFwdA)
                     : s == 2 ? ratio(c.qsFromCamera, e.qs->pdfFwdA) * neeOverOrigin
                              : ratio(c.qsFromCamera, e.qs->pdfFwdA);
    double w = usable ? connections : 0.0;
    if constexpr (kMerges)
      if (s >= 3) w += merge(s - 1, *e.qsMinus, c.qsMinusFromCamera, path.lightPath[s - 3].isDelta);
    left = power(r) * (factor(s - 1) * w + beyond);
  }
  // Camera side, the mirror image: technique t' weighs the ratios of y(t') .. y(t-1), and the
  // t' = 1 techniques count lightTracingRatio samples (Veach's n_i).
  const double lightTracingCount = power(lightTracingRatio);
  auto count = [&](int tPrime) { return tPrime == 1 ? lightTracingCount : 1.0; };
  double right = 0.0;
  if (e.ptMinus) {
    double beyond = 0.0;
    if (t >= 3) {
      const bool usable = !e.ptMinus->isDelta && !path.cameraPath[t - 3].isDelta;
      // s = 0: p_2 / p_1 also changes x0's density from next-event estimation's to the origin's.
      const double r = s == 0 ? ratio(c.ptMinusFromLight, e.ptMinus->pdfFwdA) / neeOverOrigin
                              : ratio(c.ptMinusFromLight, e.ptMinus->pdfFwdA);
      double w = usable ? count(t - 2) * connections : 0.0;
      // Technique t' = t - 2's merge merges ptMinus (s' = s + 2 >= 2), after pt (never delta: a
      // connection's end).
      if constexpr (kMerges) w += merge(2, *e.ptMinus, e.ptMinus->pdfFwdA, false);
      if constexpr (kFactors) {
        // Its mirror: technique t' = j (s' = n - j) enters at the camera vertex y(j), j >= 1.
        double sum = 0.0;
        for (int j = 1; j < t - 2; ++j)
          sum = cameraAll->step[static_cast<size_t>(j)] * (factor(n - j) * cameraAll->count[static_cast<size_t>(j)] + sum);
        beyond = power(r) * (factor(s + 2) * w + sum);
      } else {
        beyond = power(r) * (w + cameraSum[t - 2]);
      }
    }
    // Technique t' = t - 1 connects pt and its predecessor; no lens point connects to a light at
    // infinity (the path environment -> camera, s = 0, t = 2).
    // s = 0, t >= 3: the term is technique s' = 1's, which needs x0's next-event density.
    const bool usable = !e.ptMinus->isDelta && !(t == 2 && pt.isInfinite) && !(s == 0 && t >= 3 && neeRefused);
    // s = 0: technique s' = 1 samples x0 = pt by next-event estimation (x0FromLight); s = 1:
    // every technique on this side has s' >= 2, where x0 is a light subpath's origin.
    const double r = s == 0 ? ratio(x0FromLight, pt.pdfFwdA)
                     : s == 1 ? ratio(c.ptFromLight, pt.pdfFwdA) / neeOverOrigin
                              : ratio(c.ptFromLight, pt.pdfFwdA);
    double w = usable ? count(t - 1) * connections : 0.0;
    // Technique t' = t - 1's merge merges pt (s' = s + 1: not x0, s >= 1), after qs.
    if constexpr (kMerges) w += merge(s + 1, pt, pt.pdfFwdA, false);
    right = power(r) * (factor(s + 1) * w + beyond);
  }
  // Veach eq. 10.9 relative to C(s, t)'s own (n_s p_s)^beta, and with merges the merge at qs
  // (M(s, t + 1), whose density is C(s, t)'s times eta pFromCamera(qs)).
  const double own = (t == 1 ? lightTracingCount : 1.0) * factor(s);
  double sum = own + left + right;
  if constexpr (kMerges)
    sum = own * m.connections + (e.qs && e.qsMinus ? merge(s, *e.qs, c.qsFromCamera, e.qsMinus->isDelta) : 0.0) +
          left + right;
  const double w = own / sum;
  if (!std::isfinite(left + right) || !std::isfinite(w)) return std::nullopt;
  return static_cast<float>(w);
}

}  // namespace

std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const float* factors) {
  const ConnectionEnds e = connectionEnds(path);
  if (hasShortEdge(path.s, path.t, e.qs ? edgeLength2(*e.qs, *e.pt) : kNoEdge, lightSums.shortestEdge2.data(),
                   cameraSums.shortestEdge2.data(), minConnectionDistance))
    return std::nullopt;
  if (factors)
    return weightFromSums<false, true>(scene, path, e, connectionDensities(scene, camera, path, e), lightSums.sum.data(),
                                       cameraSums.sum.data(), power, lightTracingRatio, MergeTerms{}, &lightSums,
                                       &cameraSums, factors);
  return weightFromSums<false>(scene, path, e, connectionDensities(scene, camera, path, e), lightSums.sum.data(),
                               cameraSums.sum.data(), power, lightTracingRatio, MergeTerms{});
}

std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const MergeTerms& merges) {
  const ConnectionEnds e = connectionEnds(path);
  if (hasShortEdge(path.s, path.t, e.qs ? edgeLength2(*e.qs, *e.pt) : kNoEdge, lightSums.shortestEdge2.data(),
                   cameraSums.shortestEdge2.data(), minConnectionDistance))
    return std::nullopt;
  return weightFromSums<true>(scene, path, e, connectionDensities(scene, camera, path, e), lightSums.sum.data(),
                              cameraSums.sum.data(), power, lightTracingRatio, merges);
}

namespace {

template <bool kMerges, bool kFactors = false>
[[gnu::always_inline]] inline std::optional<float> interiorWeight(
    const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath, int t, const ConnectionPdfs& pdfs,
    float connectionLength2, const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums, const MisPower& power,
    float lightTracingRatio, float minConnectionDistance, const MergeTerms& merges, const float* factors = nullptr) {
  assert(s >= 2 && t >= 2);
  if (s < 2 || t < 2) __builtin_unreachable();  // lets the compiler drop weightFromSums' cases s, t <= 1
  if (hasShortEdge(s, t, connectionLength2, lightSums.shortestEdge2.data(), cameraSums.shortestEdge2.data(),
                   minConnectionDistance))
    return std::nullopt;
  const MisPath path{lightPath.data(), s, cameraPath.data(), t, nullptr, &pdfs};
  ConnectionEnds e;
  e.qsMinus = &lightPath[s - 2];
  e.qs = &lightPath[s - 1];
  e.pt = &cameraPath[t - 1];
  e.ptMinus = &cameraPath[t - 2];
  return weightFromSums<kMerges, kFactors>(scene, path, e, evaluatedConnectionDensities(*e.qs, *e.pt, pdfs, true, t),
                                           lightSums.sum.data(), cameraSums.sum.data(), power, lightTracingRatio,
                                           merges, &lightSums, &cameraSums, factors);
}

}  // namespace

std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const float* factors) {
  if (factors)
    return interiorWeight<false, true>(scene, lightPath, s, cameraPath, t, pdfs, connectionLength2, lightSums,
                                       cameraSums, power, lightTracingRatio, minConnectionDistance, MergeTerms{},
                                       factors);
  return interiorWeight<false>(scene, lightPath, s, cameraPath, t, pdfs, connectionLength2, lightSums, cameraSums,
                               power, lightTracingRatio, minConnectionDistance, MergeTerms{});
}

std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const MergeTerms& merges) {
  return interiorWeight<true>(scene, lightPath, s, cameraPath, t, pdfs, connectionLength2, lightSums, cameraSums,
                              power, lightTracingRatio, minConnectionDistance, merges);
}

MergeLightTerms mergeLightTerms(const Scene& scene, const PathVertex* lightPath, int s, const double* lightSum,
                                const float* lightShortestEdge2, const MisPower& power, const MergeTerms& m) {
  // weightFromSums' light side for the merged path C(s, t - 1) (qs = y, qsMinus = y(s-2); the path
  // has three or more vertices), with the two densities the merge fixes, X = pFromCamera(y(s-2))
  // and pFromCamera(y) = pFwd(z), left as factors.
  assert(s >= 2);
  const PathVertex& y = lightPath[s - 1];
  const PathVertex& q = lightPath[s - 2];
  const double neeOverOrigin =
      scene.lights().neeByContext() ? ratio(lightPath[0].pdfNeeA, lightPath[0].pdfFwdA) : 1.0;
  MergeLightTerms r;
  // Technique s - 2 (s = 2: q is x0, hit as an origin; s = 3: technique 1 needs x0's next-event
  // density) and its merge at y(s-3).
  const bool beyondUsable = s == 2 ? canBeHitAsOrigin(q) && !q.isDelta
                                   : !lightPath[s - 3].isDelta && !q.isDelta && (s != 3 || lightPath[0].pdfNeeA != 0.f);
  double w = beyondUsable ? m.connections : 0.0;
  if (s >= 4 && m.merges && mergeableVertex(lightPath[s - 3]))
    w += mergeTerm(power, m, lightPath[s - 3].pdfRevA, lightPath[s - 4].isDelta);
  r.beyond = w + lightSum[s - 2];
  r.beyondScale = (s == 3 ? neeOverOrigin : 1.0) / remap0(s == 2 ? q.pdfNeeA : q.pdfFwdA);
  // Technique s - 1 (s = 2: technique 1) and its merge at y(s-2).
  r.connection = !q.isDelta && (s != 2 || q.pdfNeeA != 0.f) ? m.connections : 0.0;
  r.predecessorMergeable = s >= 3 && m.merges && mergeableVertex(q);
  r.caustic = q.isDelta;
  r.predecessorCaustic = s >= 3 && lightPath[s - 3].isDelta;
  r.ownScale = (s == 2 ? neeOverOrigin : 1.0) / remap0(y.pdfFwdA);
  r.areaToPrev = y.areaToPrev;
  r.shortestEdge2 = lightShortestEdge2[s - 1];
  return r;
}

MergeCameraTerms mergeCameraTerms(const Subpath& cameraPath, int t, const SubpathMisSums& cameraSums,
                                  const MisPower& power, float lightTracingRatio, const MergeTerms& m) {
  // weightFromSums' camera side for the merged path C(s, t - 1) (s >= 2: pt = z(t-2), ptMinus =
  // z(t-3)), with pFromLight(z(t-2)) = Y left as a factor.
  assert(t >= 2);
  const PathVertex& z = cameraPath[t - 1];
  const int tc = t - 1;
  const PathVertex& pt = cameraPath[tc - 1];
  const double lightTracingCount = power(lightTracingRatio);
  auto count = [&](int tPrime) { return tPrime == 1 ? lightTracingCount : 1.0; };
  MergeCameraTerms r;
  r.pFwd = remap0(z.pdfFwdA);
  // The merge weighed, at y (always mergeable: the pass stores no other), as if y were caustic
  // (mergeWeightFromTerms applies y's keep), and the connection C(s, t - 1) of the same path,
  // unless z(t-2) is a delta vertex no connection can end at.
  r.mergeAtZ = m.merges ? mergeTerm(power, m, z.pdfFwdA, true) : 0.0;
  r.connection = pt.isDelta ? 0.0 : count(tc) * m.connections;
  r.hasCameraSide = tc >= 2;
  if (r.hasCameraSide) {
    const PathVertex& ptMinus = cameraPath[tc - 2];
    double beyond = 0.0;
    if (tc >= 3) {
      const bool usable = !ptMinus.isDelta && !cameraPath[tc - 3].isDelta;
      double w = usable ? count(tc - 2) * m.connections : 0.0;
      if (m.merges && mergeableVertex(ptMinus)) w += mergeTerm(power, m, ptMinus.pdfFwdA, pt.isDelta);
      beyond = power(ratio(ptMinus.pdfRevA, ptMinus.pdfFwdA)) * (w + cameraSums.sum[static_cast<size_t>(tc - 2)]);
    }
    // Technique t - 2 connects z(t-2) and z(t-3): not through a delta vertex, not from the lens to
    // a light at infinity; its merge at z(t-2).
    const bool usable = !ptMinus.isDelta && !(tc == 2 && pt.isInfinite) && !pt.isDelta;
    double w = usable ? count(tc - 1) * m.connections : 0.0;
    // The merge at z(t-2), after the merged vertex (never delta).
    if (m.merges && mergeableVertex(pt)) w += mergeTerm(power, m, pt.pdfFwdA, false);
    r.beyond = w + beyond;
    r.scale = 1.0 / remap0(pt.pdfFwdA);
  }
  r.areaToPrev = z.areaToPrev;
  r.shortestEdge2 = edgeLength2(z, pt);
  if (tc >= 2) r.shortestEdge2 = std::min(r.shortestEdge2, cameraSums.shortestEdge2[static_cast<size_t>(tc - 1)]);
  return r;
}

std::optional<float> mergeWeightFromTerms(const MergeLightTerms& light, const MergeCameraTerms& camera,
                                          const MergePdfs& pdfs, const MisPower& power, const MergeTerms& m,
                                          float minConnectionDistance) {
  const float minDistance2 = minConnectionDistance * minConnectionDistance;
  if (minDistance2 > 0.f && std::min(light.shortestEdge2, camera.shortestEdge2) < minDistance2) return std::nullopt;
  // The merged vertex's BSDF fixes the densities of its neighbours (mergedPathDensities).
  const double x = remap0(static_cast<double>(pdfs.towardLightW * light.areaToPrev));
  const double beyond = power(x * light.beyondScale) * light.beyond;
  double w = light.connection;
  if (light.predecessorMergeable) w += power(m.eta * mergeKeep(m.nonCaustic, light.predecessorCaustic) * x);
  const double left = power(camera.pFwd * light.ownScale) * (w + beyond);
  double right = 0.0;
  if (camera.hasCameraSide) {
    const double y = remap0(static_cast<double>(pdfs.towardCameraW * camera.areaToPrev));
    right = power(y * camera.scale) * camera.beyond;
  }
  // T(eta k_y pFwd(z)) = T(k_y) T(eta pFwd(z)) (T(x) is x^beta, or one).
  const double own = light.caustic ? camera.mergeAtZ : power(m.nonCaustic) * camera.mergeAtZ;
  const double weight = own / (camera.connection + own + left + right);
  if (!std::isfinite(left + right) || !std::isfinite(weight)) return std::nullopt;
  return static_cast<float>(weight);
}

std::optional<float> mergeWeightFromSums(const Scene& scene, const PathVertex* lightPath, int s,
                                         const double* lightSum, const float* lightShortestEdge2,
                                         const Subpath& cameraPath, int t, const SubpathMisSums& cameraSums,
                                         const MergePdfs& pdfs, const MisPower& power, float lightTracingRatio,
                                         float minConnectionDistance, const MergeTerms& merges) {
  assert(s >= 2 && t >= 2);
  return mergeWeightFromTerms(mergeLightTerms(scene, lightPath, s, lightSum, lightShortestEdge2, power, merges),
                              mergeCameraTerms(cameraPath, t, cameraSums, power, lightTracingRatio, merges), pdfs,
                              power, merges, minConnectionDistance);
}

}  // namespace pathlab
