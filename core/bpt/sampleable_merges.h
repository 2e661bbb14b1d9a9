// Which techniques of both families can produce a path, structurally (no densities): the
// connections' bits of sampleableTechniques (mis.h) joined by the merges' bits, for the
// consistency check's comparison of merges with connections (core/check/merge_bias.h).
#pragma once

#include "core/bpt/mis.h"

#include <cstdint>

namespace pathlab {

// Bits at the merge slots (Technique::slot: k - 1 + s' for M(s', n + 1 - s'), k = n - 1 the
// length) of the n-vertex path x0 .. x(n-1) held by `path` (a connection's MisPath): set where
// x(s'-1) could be the merged vertex (interior, on a surface, not scattering by a delta lobe:
// mergeableVertex in merge_mis.h). 0 for paths of more than 33 vertices (the bits would pass 63).
uint64_t mergeableTechniques(const MisPath& path);

// Every technique of its length, connections and merges, able to produce the path a merge M(s, t)
// formed: `path` is the merge's MisPath (merge_mis.h: the light prefix through the merged vertex
// y(s-1), then z(t-2) .. z0). Unlike a connection's path, its edge y(s-1) - z(t-2) was sampled
// from the camera side, so z(t-2) may be a delta vertex, and the connections through it cannot
// sample the path: every vertex's own delta flag counts.
uint64_t sampleableByMerge(const MisPath& path);

}  // namespace pathlab
