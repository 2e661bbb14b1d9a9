// weightWithMerges: the explicit weight over connections and merges.
#include "core/bpt/merge_mis.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace pathlab {

namespace {

// A path's densities and which of its vertices lie on surfaces, in per-thread scratch (as
// misWeight's: no allocation once grown).
struct PathScratch {
  PathDensities d;
  std::vector<uint8_t> surface;
};
PathScratch& densitiesOf(const Scene& scene, const Camera& camera, const MisPath& path) {
  thread_local PathScratch p;
  pathDensities(scene, camera, path, p.d);
  p.surface.resize(static_cast<size_t>(p.d.n));
  for (int i = 0; i < p.d.n; ++i) {
    const PathVertex& v = i < path.s ? lightVertex(path, i) : cameraVertex(path, p.d.n - 1 - i);
    p.surface[static_cast<size_t>(i)] = v.type == VertexType::Surface;
  }
  return p;
}

}  // namespace

double weightWithMerges(const PathDensities& d, std::span<const uint8_t> surface, Technique x,
                        const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                        float minDistance, const MergeMis& merge) {
  const int n = d.n;
  const int length = n - 1;
  const int onlySite = onlyMergeSite(d, merge);
  auto mergeUsable = [&](int sp) {
    return sp >= 2 && sp <= n - 1 && techniques.contains(Technique::merge(sp, n + 1 - sp)) &&
           mergeableVertex(d, surface, sp - 1) && (onlySite == 0 || sp == onlySite);
  };
  const UsableTechniques usable(d, techniques, minDistance);
  // The merging integrators weigh connections and merges; no equiangular technique runs beside them.
  if (x.length() != length || x.isEquiangular()) return 0.0;
  if (options.heuristic == MisHeuristic::Off) {
    // Veach 1997 sec. 9.1, both families: 1 / (enabled techniques of the length), whatever the
    // others can do; zero where x itself cannot form the path.
    const bool possible = x.isMerge() ? mergeUsable(x.s) : techniques.contains(x) && techniquePossible(d, x.s);
    if (!possible) return 0.0;
    // At the first non-specular vertex only, the merges of a length are one technique.
    int count = 0, merges = 0;
    for (const Technique y : techniquesOfLength(length, TechniqueFamilies::Connections | TechniqueFamilies::Merges))
      (y.isMerge() ? merges : count) += techniques.contains(y) ? 1 : 0;
    count += merge.firstNonSpecularOnly ? std::min(merges, 1) : merges;
    return 1.0 / static_cast<double>(count);
  }
  if (x.isMerge() ? !mergeUsable(x.s) : !usable(x.s)) return 0.0;
  if (options.heuristic == MisHeuristic::Uniform) {
    int count = 0;
    for (int sp = 0; sp < n; ++sp) count += (usable(sp) ? 1 : 0) + (mergeUsable(sp) ? 1 : 0);
    return 1.0 / static_cast<double>(count);
  }

  // Variance-aware: the balance heuristic with each technique's count times its factor (PathDensities::factors).
  const double beta = options.heuristic == MisHeuristic::Power ? static_cast<double>(options.beta) : 1.0;
  auto term = [beta](double v) { return beta == 1.0 ? v : beta == 2.0 ? v * v : std::pow(v, beta); };
  auto connectionCount = [&](int sp) {
    return (n - sp == 1 ? static_cast<double>(lightTracingRatio) : 1.0) * d.factor(sp);
  };
  // A zero camera-side density at the merged vertex is a delta lobe next to it (the vertex itself
  // is not delta): it counts one, as in the ratios, and cancels against C(s'-1), which samples
  // the merged vertex from the camera side through the same lobe.
  // The pass kept x(s'-1) with probability mergeKeep, by x(s'-2)'s delta flag.
  auto mergeFactor = [&](int sp) {
    return merge.eta * mergeKeep(merge.nonCaustic, d.delta[static_cast<size_t>(sp - 2)]) *
           remap0(d.pFromCamera[static_cast<size_t>(sp - 1)]) * d.factor(length - 1 + sp);
  };
  // n_x p_x relative to p_C(x.s).
  const double own = x.isMerge() ? mergeFactor(x.s) : connectionCount(x.s);
  // r = p_C(s') / p_C(x.s), walked outward from x.s (Veach eq. 10.10, mis.h's ratios), so that no
  // density of a whole path is formed on its own; each s' adds its connection and its merge.
  double sum = 0.0;
  auto add = [&](int sp, double r) {
    if (usable(sp)) sum += term(r * connectionCount(sp) / own);
    if (mergeUsable(sp)) sum += term(r * mergeFactor(sp) / own);
  };
  add(x.s, 1.0);
  double r = 1.0;
  for (int sp = x.s + 1; sp < n; ++sp) add(sp, r *= ratioToLight(d, sp));
  r = 1.0;
  for (int sp = x.s - 1; sp >= 0; --sp) add(sp, r *= ratioToCamera(d, sp));
  const double w = 1.0 / sum;
  return std::isfinite(w) ? w : 0.0;
}

float weightWithMerges(const Scene& scene, const Camera& camera, const MisPath& path, Technique x,
                       const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                       float minDistance, const MergeMis& merge, const float* factors) {
  if (!techniques.contains(x)) return 0.f;
  if (!x.isMerge() && path.t == 1 && camera.isOrthographic()) return 0.f;
  PathScratch& p = densitiesOf(scene, camera, path);
  p.d.factors = factors;
  // A merge's z(t-2), the connection's camera end here, keeps its walk's delta flag: where it is a
  // mirror the connections through it cannot sample the merged path (mergedPathDensities).
  if (x.isMerge()) p.d.delta[static_cast<size_t>(path.s)] = cameraVertex(path, path.t - 1).isDelta;
  const double w = weightWithMerges(p.d, p.surface, x, techniques, options, lightTracingRatio, minDistance, merge);
  return std::isfinite(w) ? static_cast<float>(w) : 0.f;
}

void mergedPathDensities(const PathVertex* lightPath, int s, const PathVertex* cameraPath, int t, const MergePdfs& pdfs,
                         PathDensities& d, std::vector<uint8_t>& surface) {
  const int n = s + t - 1;
  d.n = n;
  d.factors = nullptr;
  d.pFromLight.resize(static_cast<size_t>(n));
  d.pFromCamera.resize(static_cast<size_t>(n));
  d.delta.resize(static_cast<size_t>(n));
  d.edgeLength2.resize(static_cast<size_t>(n - 1));
  surface.resize(static_cast<size_t>(n));
  // x_i: the light walk's vertex i < s (the merged one, i = s - 1, at y(s-1)'s place for its edge
  // to x(s-2)), the camera walk's z(n-1-i) beyond.
  auto at = [&](int i) -> const PathVertex& { return i < s ? lightPath[i] : cameraPath[n - 1 - i]; };
  for (int i = 0; i < n; ++i) {
    const PathVertex& v = at(i);
    const size_t k = static_cast<size_t>(i);
    d.pFromLight[k] = i < s ? v.pdfFwdA : v.pdfRevA;
    d.pFromCamera[k] = i < s ? v.pdfRevA : v.pdfFwdA;
    d.delta[k] = v.isDelta;
    surface[k] = v.type == VertexType::Surface;
  }
  const PathVertex& y = lightPath[s - 1];
  const PathVertex& z = cameraPath[t - 1];
  const size_t merged = static_cast<size_t>(s - 1);
  d.pFromCamera[merged] = z.pdfFwdA;
  d.delta[merged] = false;
  surface[merged] = 1;
  d.pFromCamera[merged - 1] = pdfs.towardLightW * y.areaToPrev;
  d.pFromLight[merged + 1] = pdfs.towardCameraW * z.areaToPrev;
  for (int i = 0; i + 1 < n; ++i)
    d.edgeLength2[static_cast<size_t>(i)] = i == s - 1 ? edgeLength2(z, cameraPath[t - 2]) : edgeLength2(at(i), at(i + 1));
  d.x0CanBeHit = canBeHitAsOrigin(lightPath[0]);
  d.x0Infinite = lightPath[0].isInfinite;
  // The light choice the light walk stored for its x1 (n >= 3 here).
  d.x0Nee = lightPath[0].pdfNeeA;
  d.neeRefused = d.x0Nee == 0.0;
}

float mergeWeight(const PathVertex* lightPath, int s, const PathVertex* cameraPath, int t, const MergePdfs& pdfs,
                  const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio, float minDistance,
                  const MergeMis& merge, const float* factors) {
  thread_local PathScratch p;
  mergedPathDensities(lightPath, s, cameraPath, t, pdfs, p.d, p.surface);
  p.d.factors = factors;
  const double w = weightWithMerges(p.d, p.surface, Technique::merge(s, t), techniques, options, lightTracingRatio,
                                    minDistance, merge);
  return std::isfinite(w) ? static_cast<float>(w) : 0.f;
}

double weightSumWithMerges(const Scene& scene, const Camera& camera, const MisPath& path,
                           const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                           float minDistance, const MergeMis& merge, const float* factors) {
  PathScratch& p = densitiesOf(scene, camera, path);
  p.d.factors = factors;
  double sum = 0.0;
  for (const Technique x : techniquesOfLength(p.d.n - 1, TechniqueFamilies::Connections | TechniqueFamilies::Merges))
    sum += weightWithMerges(p.d, p.surface, x, techniques, options, lightTracingRatio, minDistance, merge);
  return sum;
}

}  // namespace pathlab
