// One path, every technique (the seed's figure of a path of length k sampled by its k + 1
// techniques; Veach 1997 sec. 10.2-10.3): for the path a connection formed, the area-measure
// density with which each technique (s', t') would sample this very path, whether it can at all,
// which edge it connects (the terms of f it does not importance-sample), and its MIS weight
// under the balance, power and uniform heuristics among the enabled techniques.
#pragma once

#include "core/bpt/merge_mis.h"
#include "core/bpt/mis.h"
#include "core/bpt/technique_result.h"

#include <optional>
#include <vector>

namespace pathlab {

// The merges' share of a pass (merge_pass.h): the radius r and eta = pi r^2 N, N its light subpaths.
struct MergesOnPath {
  MergeMis mis;
  float radius = 0.f;
};

// Every technique of the path's length for the path `path` forms, in slot order (Technique::slot:
// the connections by s', then, with `merges`, the merges M(s', n + 1 - s') by s', else the
// equiangular technique E(1, n - 1) where it is sampled and can sample the path; findOnPath
// finds one); `options` gives
// beta for the power heuristic and the minimum connection. With `merges` every weight is the one
// over connections and merges together (weightWithMerges) on the path `path` forms. `factors`:
// variance-aware MIS's factors of the path's length where it lands (PathDensities::factors), in
// its weight only; `counts`: each technique's samples per camera sample (--light-paths,
// core/bpt/light_paths.h), in every heuristic's weight (null: one each). Not both.
std::vector<TechniqueOnPath> techniquesOnPath(const Scene& scene, const Camera& camera, const MisPath& path,
                                              const TechniqueSet& techniques, const MisOptions& options,
                                              float lightTracingRatio = 1.f,
                                              const std::optional<MergesOnPath>& merges = std::nullopt,
                                              const float* factors = nullptr, const float* counts = nullptr);

// A merge's path as its weight sees it (mergedPathDensities): the densities, and which vertices
// lie on surfaces.
struct MergedPath {
  PathDensities densities;
  std::vector<uint8_t> surface;
};

// The same for merge M(s, t) on its merged path `merged` (the render's weights: the merged vertex
// keeps both walks' densities and scatters by z(t-1)'s BSDF), `path` being the connection
// C(s, t - 1) through the same vertices (for which techniques can sample it at all).
std::vector<TechniqueOnPath> techniquesOnMergedPath(const Scene& scene, const MisPath& path, const MergedPath& merged,
                                                    const TechniqueSet& techniques, const MisOptions& options,
                                                    float lightTracingRatio, const MergesOnPath& merges,
                                                    const float* factors = nullptr);

// The full path `path` forms, light end first, with both densities of every vertex (TracedPath),
// into `out` (its storage reused); `densities`: those instead of the path's own (a merged path).
void tracePath(const Scene& scene, const Camera& camera, const MisPath& path, TracedPath& out,
               const PathDensities* densities = nullptr);

}  // namespace pathlab
