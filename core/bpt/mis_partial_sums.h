// The MIS weight in O(1) per connection when every technique is enabled: running partial sums
// of the other techniques' density ratios, accumulated once per subpath vertex and patched with
// the connection's own densities (Georgiev 2012, "Implementing Vertex Connection and Merging",
// the dVC quantities; SmallVCM vertexcm.hxx). misWeight (mis.h) stays the reference: for
// technique subsets, for paths with near-coincident connections, and as this one's test oracle.
//
// With r_i = pFromCamera(x_i) / pFromLight(x_i) (delta densities remapped to one) on the light
// side, Veach's weight of technique s (eq. 10.9 with the ratios of eq. 10.10) has the sum
//   left(s) = sum_{s' < s} u(s') prod_{i = s'}^{s-1} T(r_i),  T(x) = x^beta (1 for uniform),
// u(s') = 1 when technique s' can produce the path (no delta vertex at its connection). It obeys
//   left(s) = T(r_{s-1}) (u(s-1) + left(s-1)),
// so left(s - 2), which holds only densities the walk fixed, is stored per vertex, and the two
// ratios the connection changes (r_{s-1}, r_{s-2}) are applied on top. The camera side is the
// mirror image with 1 / r and the light-tracing sample count on its t' = 1 term.
//
// Vertex merging (merge_mis.h) adds to each s' its merge at x(s'-1): the count u(s') becomes
//   w(s') = c u(s') + m(s') T(eta pFromCamera(x(s'-1))),
// c one when every connection is enabled and zero when none is, m(s') one where every merge is
// enabled and x(s'-1) can be merged (Georgiev et al. 2012 eq. 11; SmallVCM's dVM quantities). A
// merge's pFromCamera on the light side is the reverse density the walk stored (pdfRevA) except
// at the two vertices the connection changes, and on the camera side the forward density: so the
// same recursion, with the same two patches, gives the weights over connections and merges.
#pragma once

#include "core/bpt/mis.h"
#include "core/bpt/subpath.h"

#include <optional>
#include <vector>

namespace pathlab {

// The heuristic's power of a density ratio: x (balance), x^beta (power), 1 (uniform: the sums
// then count the techniques).
struct MisPower {
  MisHeuristic heuristic = MisHeuristic::Balance;
  double beta = 1.0;
  explicit MisPower(const MisOptions& options)
      : heuristic(options.heuristic), beta(options.heuristic == MisHeuristic::Power ? options.beta : 1.0) {}
  double operator()(double x) const {
    if (heuristic == MisHeuristic::Uniform) return 1.0;
    return beta == 1.0 ? x : beta == 2.0 ? x * x : std::pow(x, beta);
  }
};

// The merges' part of the sums: which families are enabled (each all or nothing: a subset is
// misWeight's or weightWithMerges' job) and the pass's eta = pi r^2 N. The default adds nothing.
struct MergeTerms {
  double connections = 1.0;  // 1: every connection enabled; 0: none (bpm)
  bool merges = false;       // every merge enabled
  double eta = 0.0;
  double nonCaustic = 1.0;   // MergePass::nonCaustic (mergeKeep)
};

// The probability that a pass keeps light vertex x_i for merging (MergePass::index): one when the
// light walk reached it by a delta bounce, x(i-1) scattering by a delta lobe (a caustic: light,
// mirror or glass, then x_i), else `nonCaustic`. One for every vertex is Georgiev et al.'s VCM;
// below one the pass thins the other light vertices and the survivors carry 1 / keep. A merge at
// x_i then has the density of the one that kept every vertex times keep: it multiplies eta in
// every merge term (n_M p_M(s') = eta keep(x(s'-1)) pFromCamera(x(s'-1)) p_C(s')), a function of
// the path's delta flags alone, so the weights stay a partition of unity.
inline double mergeKeep(double nonCaustic, bool lightPredecessorDelta) {
  return lightPredecessorDelta ? 1.0 : nonCaustic;
}

// A vertex a merge may take as its merged vertex: on a surface, not scattered by a delta lobe (an
// interior vertex: callers rule out x0 and the camera).
inline bool mergeableVertex(const PathVertex& v) { return v.type == VertexType::Surface && !v.isDelta; }

// Per subpath: sum[i] is the partial sum of the prefix of i vertices (left(i) on the light side,
// its mirror on the camera side), shortestEdge2[i] the squared length of the shortest edge among
// vertices 0..i (infinite for one vertex).
//
// Variance-aware MIS (variance_aware_mis.h) multiplies each technique's count by a factor of the
// path's length, which a walk does not know yet: with `steps`, the recursion's two parts per vertex
// are kept too, count[i] = w(s' = i) (light side; t' = i on the camera side) and step[i] = T(r_i),
// so that a connection sums left(s - 2) = step[s-3] (c count[s-3] + step[s-4] (...)) again with the
// factors c of its length, in O(s) multiply-adds (connections only: with merges the weights are the
// explicit ones).
struct SubpathMisSums {
  std::vector<double> sum;
  std::vector<float> shortestEdge2;
  std::vector<double> step, count;  // only when accumulated with `steps`
};

// `steps`: keep SubpathMisSums::step and ::count (variance-aware MIS; no merges).
void accumulateLightSums(const Subpath& lightPath, const MisPower& power, SubpathMisSums& sums,
                         const MergeTerms& merges = {}, bool steps = false);
// The same on `count` stored vertices (a merge pass's light subpath): sum[i] and shortestEdge2[i]
// for i < count written to sum[i], shortestEdge2[i] (no sum[count]).
void accumulateLightSums(const PathVertex* lightPath, int count, const MisPower& power, double* sum,
                         float* shortestEdge2, const MergeTerms& merges = {});
// lightTracingRatio: the sample count of the t' = 1 techniques (bidir_tracer.h).
void accumulateCameraSums(const Subpath& cameraPath, const MisPower& power, float lightTracingRatio,
                          SubpathMisSums& sums, const MergeTerms& merges = {}, bool steps = false);

// The weight of technique (path.s, path.t) among all techniques of its length, from the sums of
// the subpaths path.lightPath and path.cameraPath point into. nullopt where the sums cannot give
// it and misWeight must: an edge shorter than minConnectionDistance (MisOptions::minConnection),
// or a sum that overflowed.
// `factors`: variance-aware MIS's factors of the path's length by slot (PathDensities::factors),
// read with the sums' steps; null: every factor 1.
std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const float* factors = nullptr);
// The same among the connections and merges `merges` enables (sums accumulated with them).
std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const MergeTerms& merges);

// misWeightFromSums of an interior technique (s, t >= 2) whose connection formInteriorConnection
// formed (its densities `pdfs`, its squared length connectionLength2), the same bits, without the
// general case's dispatch: the tracer's interior connections (BidirTracer::weight). s and t below
// 2 are undefined behaviour (the compiler is told they cannot happen).
std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const float* factors = nullptr);
std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance,
                                       const MergeTerms& merges);

// The densities a merge M(s, t) fixes beside its walks' (merge_mis.h mergedPathDensities): at the
// merged vertex the camera vertex z(t-1)'s BSDF between its own direction and the light vertex
// y(s-1)'s, in solid angle: toward y(s-2) (the camera side continuing) and toward z(t-2) (the
// light side continuing) (BsdfEval::pdfFwdW and pdfRevW of eval(z.wo, y.wo)).
struct MergePdfs {
  float towardLightW = 0.f;
  float towardCameraW = 0.f;
};

// A merge's weight split into what its light vertex fixes and what its camera vertex fixes, so
// that a pass stores the first once per light vertex and a camera vertex computes the second once
// for all the light vertices it finds (SmallVCM's dVCM / dVC / dVM per vertex, here in this file's
// partial-sum form). With X = pFromCamera(y(s-2)) = towardLightW areaToPrev(y) and
// Y = pFromLight(z(t-2)) = towardCameraW areaToPrev(z), the two densities the merged vertex's BSDF
// fixes, the weight of M(s, t) on its merged path C(s, t - 1) (mergedPathDensities) is
//   left  = T(r_y) (c_y + m_y T(eta X) + T(X K_b) B),   r_y = pFwd(z) K_y,
//   right = T(Y K_z) B_z,
//   w = T(eta k_y pFwd(z)) / (c_z + T(eta k_y pFwd(z)) + left + right),
// with k the keep probabilities of the merged vertices (mergeKeep; m_y's term has eta k_q X),
// every other factor fixed by one walk alone (the members below).
struct MergeLightTerms {
  double beyond = 0.0;         // B: w(s-2) + left(s-2), the terms beyond y(s-2)
  double beyondScale = 0.0;    // K_b: X K_b is r_{s-2}
  double ownScale = 0.0;       // K_y: pFwd(z) K_y is r_{s-1}
  float connection = 0.f;      // c_y: the connection C(s-1, .) counted (connections, or 0 if unusable)
  float areaToPrev = 0.f;      // y's: X = towardLightW areaToPrev
  float shortestEdge2 = 0.f;   // the light prefix's shortest edge (hasShortEdge)
  bool predecessorMergeable = false;  // m_y: the merge at y(s-2) counted
  bool caustic = false;               // y(s-2) is a delta vertex: y kept with probability one (mergeKeep)
  bool predecessorCaustic = false;    // y(s-3) is: the same for the merge at y(s-2)
};
struct MergeCameraTerms {
  double mergeAtZ = 0.0;       // T(eta pFwd(z)): the weighed merge's own term
  double pFwd = 0.0;           // pFwd(z), remapped
  double connection = 0.0;     // c_z: C(s, t - 1), unless z(t-2) is a delta vertex
  double beyond = 0.0;         // B_z: the camera side's terms from z(t-2) on
  double scale = 0.0;          // K_z: Y K_z is the ratio at z(t-2)
  float areaToPrev = 0.f;      // z's: Y = towardCameraW areaToPrev
  float shortestEdge2 = 0.f;   // the camera prefix's and the edge z(t-1) -> z(t-2), shortest
  bool hasCameraSide = false;  // t >= 3: a technique t' < t - 1 exists (right > 0 possible)
};

// lightPath[s - 1] (s >= 2, mergeable) with its stored sums (accumulateLightSums' pointer form).
MergeLightTerms mergeLightTerms(const Scene& scene, const PathVertex* lightPath, int s, const double* lightSum,
                                const float* lightShortestEdge2, const MisPower& power, const MergeTerms& merges);
// cameraPath[t - 1] (t >= 2, mergeable) with its subpath's sums.
MergeCameraTerms mergeCameraTerms(const Subpath& cameraPath, int t, const SubpathMisSums& cameraSums,
                                  const MisPower& power, float lightTracingRatio, const MergeTerms& merges);
// The weight from the two; nullopt as misWeightFromSums' (a short edge, a sum that overflowed).
std::optional<float> mergeWeightFromTerms(const MergeLightTerms& light, const MergeCameraTerms& camera,
                                          const MergePdfs& pdfs, const MisPower& power, const MergeTerms& merges,
                                          float minConnectionDistance);

// The weight of merge M(s, t) of light vertex lightPath[s - 1] (a stored light subpath, its sums
// lightSum / lightShortestEdge2 per vertex as accumulateLightSums' pointer form wrote them) and
// camera vertex cameraPath[t - 1] among the techniques `merges` enables: the path and densities
// of mergedPathDensities, in O(1) (the two terms above, formed and combined). nullopt as
// misWeightFromSums'.
std::optional<float> mergeWeightFromSums(const Scene& scene, const PathVertex* lightPath, int s,
                                         const double* lightSum, const float* lightShortestEdge2,
                                         const Subpath& cameraPath, int t, const SubpathMisSums& cameraSums,
                                         const MergePdfs& pdfs, const MisPower& power, float lightTracingRatio,
                                         float minConnectionDistance, const MergeTerms& merges);

}  // namespace pathlab
