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

void accumulateShortestEdges(const Subpath& path, SubpathMisSums& sums) {
  sums.shortestEdge2.resize(static_cast<size_t>(std::max(path.count, 1)));
  sums.shortestEdge2[0] = kNoEdge;
  for (int i = 1; i < path.count; ++i)
    sums.shortestEdge2[static_cast<size_t>(i)] =
        std::min(sums.shortestEdge2[static_cast<size_t>(i - 1)], edgeLength2(path[i - 1], path[i]));
}

}  // namespace

void accumulateLightSums(const Subpath& path, const MisPower& power, SubpathMisSums& sums) {
  sums.sum.resize(static_cast<size_t>(path.count) + 1);
  double left = 0.0;
  sums.sum[0] = left;
  for (int i = 0; i < path.count; ++i) {
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
    left = power(r) * ((usable ? 1.0 : 0.0) + left);
    sums.sum[static_cast<size_t>(i) + 1] = left;
  }
  accumulateShortestEdges(path, sums);
}

void accumulateCameraSums(const Subpath& path, const MisPower& power, float lightTracingRatio,
                          SubpathMisSums& sums) {
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
    right = power(ratio(v.pdfRevA, v.pdfFwdA)) * ((usable ? count : 0.0) + right);
    sums.sum[static_cast<size_t>(j) + 1] = right;
  }
  accumulateShortestEdges(path, sums);
}

namespace {

// An edge of the path shorter than minConnectionDistance: the prefixes' shortest edges (the fresh
// endpoint of s = 1 or t = 1 stands alone on its side) and the connection's own, connection2
// (infinite when there is none: s = 0).
[[gnu::always_inline]] inline bool hasShortEdge(int s, int t, float connection2, const SubpathMisSums& lightSums,
                                                const SubpathMisSums& cameraSums, float minConnectionDistance) {
  const float minDistance2 = minConnectionDistance * minConnectionDistance;
  if (!(minDistance2 > 0.f)) return false;
  float shortest = kNoEdge;
  if (s >= 2) shortest = std::min(shortest, lightSums.shortestEdge2[static_cast<size_t>(s - 1)]);
  if (t >= 2) shortest = std::min(shortest, cameraSums.shortestEdge2[static_cast<size_t>(t - 1)]);
  shortest = std::min(shortest, connection2);
  return shortest < minDistance2;
}

// The weight from the sums once the connection's densities are known: both entry points below.
// Inline into each, so that the interior one (s, t >= 2 known) loses the branches of s <= 1.
[[gnu::always_inline]] inline std::optional<float> weightFromSums(const Scene& scene, const MisPath& path,
                                                                  const ConnectionEnds& e, const ConnectionDensities& c,
                                                                  const SubpathMisSums& lightSums,
                                                                  const SubpathMisSums& cameraSums, const MisPower& power,
                                                                  float lightTracingRatio) {
  const int s = path.s, t = path.t;
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
  // Light side: left(s) = T(r_{s-1}) (u(s-1) + T(r_{s-2}) (u(s-2) + left(s-2))). qs and pt count
  // as non-delta (connect() formed the path through them).
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
      beyond = power(r) * ((usable ? 1.0 : 0.0) + lightSums.sum[static_cast<size_t>(s - 2)]);
    }
    // s = 2: the term is technique s' = 1's.
    const bool usable = s == 1 ? canBeHitAsOrigin(*e.qs) : !e.qsMinus->isDelta && (s != 2 || e.qsMinus->pdfNeeA != 0.f);
    // s = 1: qs is x0, sampled by next-event estimation unless it meets the lens (t = 1);
    // s = 2: qs is x1 (r_1).
    const double r = s == 1   ? ratio(c.qsFromCamera, n >= 3 ? e.qs->pdfNeeA : e.qs->pdfFwdA)
                     : s == 2 ? ratio(c.qsFromCamera, e.qs->pdfFwdA) * neeOverOrigin
                              : ratio(c.qsFromCamera, e.qs->pdfFwdA);
    left = power(r) * ((usable ? 1.0 : 0.0) + beyond);
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
      beyond = power(r) * ((usable ? count(t - 2) : 0.0) + cameraSums.sum[static_cast<size_t>(t - 2)]);
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
    right = power(r) * ((usable ? count(t - 1) : 0.0) + beyond);
  }
  // Veach eq. 10.9 relative to the technique's own (n_s p_s)^beta.
  const double own = t == 1 ? lightTracingCount : 1.0;
  const double w = own / (own + left + right);
  if (!std::isfinite(left + right) || !std::isfinite(w)) return std::nullopt;
  return static_cast<float>(w);
}

}  // namespace

std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance) {
  const ConnectionEnds e = connectionEnds(path);
  if (hasShortEdge(path.s, path.t, e.qs ? edgeLength2(*e.qs, *e.pt) : kNoEdge, lightSums, cameraSums,
                   minConnectionDistance))
    return std::nullopt;
  return weightFromSums(scene, path, e, connectionDensities(scene, camera, path, e), lightSums, cameraSums, power,
                        lightTracingRatio);
}

std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance) {
  assert(s >= 2 && t >= 2);
  if (s < 2 || t < 2) __builtin_unreachable();  // lets the compiler drop weightFromSums' cases s, t <= 1
  if (hasShortEdge(s, t, connectionLength2, lightSums, cameraSums, minConnectionDistance)) return std::nullopt;
  const MisPath path{lightPath.data(), s, cameraPath.data(), t, nullptr, &pdfs};
  ConnectionEnds e;
  e.qsMinus = &lightPath[s - 2];
  e.qs = &lightPath[s - 1];
  e.pt = &cameraPath[t - 1];
  e.ptMinus = &cameraPath[t - 2];
  return weightFromSums(scene, path, e, evaluatedConnectionDensities(*e.qs, *e.pt, pdfs, true, t), lightSums,
                        cameraSums, power, lightTracingRatio);
}

}  // namespace pathlab
