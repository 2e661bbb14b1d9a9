// One path, every technique (the seed's figure of a path of length k sampled by its k + 1
// techniques; Veach 1997 sec. 10.2-10.3): for the path a connection formed, the area-measure
// density with which each technique (s', t') would sample this very path, whether it can at all,
// which edge it connects (the terms of f it does not importance-sample), and its MIS weight
// under the balance, power and uniform heuristics among the enabled techniques.
#pragma once

#include "core/bpt/mis.h"
#include "core/bpt/technique_result.h"

#include <vector>

namespace pathlab {

// Every technique of the path's length for the path `path` forms, in s' order; `options` gives
// beta for the power heuristic and the minimum connection.
std::vector<TechniqueOnPath> techniquesOnPath(const Scene& scene, const Camera& camera, const MisPath& path,
                                              const TechniqueSet& techniques, const MisOptions& options,
                                              float lightTracingRatio = 1.f);

// The full path `path` forms, light end first, with both densities of every vertex (TracedPath),
// into `out` (its storage reused).
void tracePath(const Scene& scene, const Camera& camera, const MisPath& path, TracedPath& out);

}  // namespace pathlab
