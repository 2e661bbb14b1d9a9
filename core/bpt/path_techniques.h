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
// the connections by s', then, with `merges`, the merges M(s', n + 1 - s') by s'); `options` gives
// beta for the power heuristic and the minimum connection. With `merges` every weight is the one
// over connections and merges together (weightWithMerges); for a merge M(s, t) `path` is the
// MisPath of the connection C(s, t - 1) that joins the same vertices (merge_mis.h).
std::vector<TechniqueOnPath> techniquesOnPath(const Scene& scene, const Camera& camera, const MisPath& path,
                                              const TechniqueSet& techniques, const MisOptions& options,
                                              float lightTracingRatio = 1.f,
                                              const std::optional<MergesOnPath>& merges = std::nullopt);

// The full path `path` forms, light end first, with both densities of every vertex (TracedPath),
// into `out` (its storage reused).
void tracePath(const Scene& scene, const Camera& camera, const MisPath& path, TracedPath& out);

}  // namespace pathlab
