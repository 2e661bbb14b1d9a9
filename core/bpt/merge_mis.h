// Multiple importance sampling over connections and merges (vertex connection and merging:
// Georgiev, Křivánek, Davidovič and Slusallek 2012, sec. 4; Hachisuka, Pantaleoni and Jensen 2012):
// the explicit O(n) weight over a path's densities, the oracle of any faster form.
#pragma once

#include "core/bpt/mis.h"
#include "core/bpt/mis_partial_sums.h"

#include <span>

namespace pathlab {

// A merge M(s', n + 1 - s') of an n-vertex path x0 .. x(n-1) takes x(s'-1) from both sides: the
// light subpath samples x0 .. x(s'-1), a camera subpath samples x(n-1) .. x(s'-1) and the two
// ends are accepted within a radius r. Its density is the connection C(s')'s, which samples
// x(s'-1) from the light side only, times the acceptance probability pi r^2 pFromCamera(x(s'-1))
// (Georgiev et al. eq. 10), and every light subpath of the pass serves every camera sample, so its
// sample count is N. The merges enter every weight through eta = pi r^2 N (eq. 11):
//   n_M p_M(s') = eta * pFromCamera(x(s'-1)) * p_C(s').
struct MergeMis {
  double eta = 0.0;
  // MergeSite::FirstNonSpecular (progressive photon mapping): a merge at x(s'-1) counts only when
  // every vertex between it and the camera, x(s') .. x(n-2), scattered by a delta lobe.
  bool firstNonSpecularOnly = false;
  // MergePass::nonCaustic: a merge at x(s'-1) has eta times its keep probability (mergeKeep).
  double nonCaustic = 1.0;
};

// Whether x_i can be the merged vertex: interior (not x0 on the light, not the camera x(n-1)),
// on a surface, not scattering by a delta lobe (a merge needs a density there). The caller, who
// has the vertices, says which are surfaces.
inline bool mergeableVertex(const PathDensities& d, std::span<const uint8_t> surface, int i) {
  return i >= 1 && i <= d.n - 2 && surface[static_cast<size_t>(i)] && !d.delta[static_cast<size_t>(i)];
}

// The one s' whose merge M(s', n + 1 - s') may sample the path when merges happen at the first
// non-specular camera vertex only (ppm): x(s'-1) is that vertex, every vertex after it, x(s') ..
// x(n-2), scattered by a delta lobe. 0 when merges happen at every vertex (any s' may).
inline int onlyMergeSite(const PathDensities& d, const MergeMis& merge) {
  if (!merge.firstNonSpecularOnly) return 0;
  int first = d.n - 1;
  while (first >= 2 && d.delta[static_cast<size_t>(first - 1)]) --first;
  return first;
}

// The weight of technique x of the n-vertex path whose densities are d (a connection C(s, n - s) or
// a merge M(s, n + 1 - s)) among the enabled connections able to produce it (UsableTechniques, as
// misWeight) and the enabled merges at mergeable vertices; `surface[i]`: x_i lies on a surface.
// Balance and power: (n_x p_x)^beta / sum over them of (n_j p_j)^beta; uniform: one over their
// number; MisHeuristic::Off: one over the enabled techniques of the path's length of both kinds.
// Zero when x itself is disabled or impossible. With no merge enabled it is misWeight's weight.
double weightWithMerges(const PathDensities& d, std::span<const uint8_t> surface, Technique x,
                        const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                        float minDistance, const MergeMis& merge);

// The same on a path as the tracer holds it: a connection C(s, t)'s MisPath for x = C(s, t); for a
// merge M(s, t), the MisPath of the connection C(s, t - 1) that joins the same vertices (the light
// prefix through the merged vertex y(s-1), then z(t-2) .. z0), the merged vertex taken as y(s-1).
// `factors`: variance-aware MIS's factors of the path's length at its pixel (PathDensities::factors).
float weightWithMerges(const Scene& scene, const Camera& camera, const MisPath& path, Technique x,
                       const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                       float minDistance, const MergeMis& merge, const float* factors = nullptr);

// The path a merge M(s, t) of light vertex y(s-1) (lightPath[s - 1]) and camera vertex z(t-1)
// (cameraPath[t - 1]) stands for, n = s + t - 1 vertices x0 .. x(s-2), X, z(t-2) .. z0, and its
// densities (Georgiev et al. 2012 sec. 4.2, as SmallVCM weighs a merge): the merged vertex X
// keeps both walks' densities of it (y's pdfFwdA from the light, z's pdfFwdA from the camera) and
// scatters by z's BSDF between z's direction and y's (MergePdfs, converted to area by y's and z's
// areaToPrev); every other density is its walk's. The two ends lie within r of each other, so
// this is the connection C(s, t - 1) through y(s-1) up to O(r): exactly what the merge's weight
// needs and the O(1) form (mergeWeightFromSums) computes. `surface[i]`: x_i lies on a surface.
void mergedPathDensities(const PathVertex* lightPath, int s, const PathVertex* cameraPath, int t, const MergePdfs& pdfs,
                         PathDensities& d, std::vector<uint8_t>& surface);

// The explicit weight of merge M(s, t) on its merged path (mergedPathDensities): the oracle of
// mergeWeightFromSums and its fallback.
float mergeWeight(const PathVertex* lightPath, int s, const PathVertex* cameraPath, int t, const MergePdfs& pdfs,
                  const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio, float minDistance,
                  const MergeMis& merge, const float* factors = nullptr);

// The sum over every technique of the path's length, both families, of weightWithMerges on this
// connection's path: one when the weights are a partition of unity (the MIS check, checkMis).
double weightSumWithMerges(const Scene& scene, const Camera& camera, const MisPath& path,
                           const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                           float minDistance, const MergeMis& merge, const float* factors = nullptr);

}  // namespace pathlab
