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

// Per subpath: sum[i] is the partial sum of the prefix of i vertices (left(i) on the light side,
// its mirror on the camera side), shortestEdge2[i] the squared length of the shortest edge among
// vertices 0..i (infinite for one vertex).
struct SubpathMisSums {
  std::vector<double> sum;
  std::vector<float> shortestEdge2;
};

void accumulateLightSums(const Subpath& lightPath, const MisPower& power, SubpathMisSums& sums);
// lightTracingRatio: the sample count of the t' = 1 techniques (bidir_tracer.h).
void accumulateCameraSums(const Subpath& cameraPath, const MisPower& power, float lightTracingRatio,
                          SubpathMisSums& sums);

// The weight of technique (path.s, path.t) among all techniques of its length, from the sums of
// the subpaths path.lightPath and path.cameraPath point into. nullopt where the sums cannot give
// it and misWeight must: an edge shorter than minConnectionDistance (MisOptions::minConnection),
// or a sum that overflowed.
std::optional<float> misWeightFromSums(const Scene& scene, const Camera& camera, const MisPath& path,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance);

// misWeightFromSums of an interior technique (s, t >= 2) whose connection formInteriorConnection
// formed (its densities `pdfs`, its squared length connectionLength2), the same bits, without the
// general case's dispatch: the tracer's interior connections (BidirTracer::weight). s and t below
// 2 are undefined behaviour (the compiler is told they cannot happen).
std::optional<float> misWeightInterior(const Scene& scene, const Subpath& lightPath, int s, const Subpath& cameraPath,
                                       int t, const ConnectionPdfs& pdfs, float connectionLength2,
                                       const SubpathMisSums& lightSums, const SubpathMisSums& cameraSums,
                                       const MisPower& power, float lightTracingRatio, float minConnectionDistance);

}  // namespace pathlab
