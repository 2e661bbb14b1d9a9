// Which techniques of a path's length, connections and merges, could sample that very path: the
// technique maps' "cannot sample" (core/maps/) once vertex merging is in the technique set.
#pragma once

#include "core/bpt/bidir_options.h"
#include "core/bpt/mis.h"

#include <cstdint>

namespace pathlab {

// sampleableTechniques (mis.h) over both families: bit Technique::slot() of every technique of
// the path's length k = n - 1 able to produce it. Connections as sampleableTechniques; the merge
// M(s', n + 1 - s') (slot k - 1 + s', 2 <= s' <= k) when its merged vertex x(s'-1) could be
// merged: interior (by the range of s'), on a surface, not scattered by a delta lobe
// (mergeableVertex, merge_mis.h, on the same delta flags). Structural, independent of which
// techniques are enabled, of the radius and of walk lengths, like the connections' bits.
//
// `formedBy` says whose path `path` is: a connection C(s, t)'s MisPath, whose joined ends x(s-1),
// x(s) are not delta (pathDensities' patches), or a merge M(s, t)'s, given as the MisPath of C(s,
// t - 1) that holds the same vertices (merged vertex y(s-1), then z(t-2) .. z0; weightWithMerges'
// convention). In a merge's path the edge y(s-1) -- z(t-2) was sampled by the camera walk, not
// connected, so z(t-2) keeps its own delta flag: a merge seen in a mirror is not sampleable by the
// two connections at the mirror. Slots past 63 (merges of paths longer than 32 edges) are left
// out, as the pyramid's sampleable films skip them; 0 past kSampleableBits vertices.
// `site` FirstNonSpecular (ppm): a merge only where the camera subpath merges, at its first vertex
// that is not a delta scatter (every vertex between it and the camera delta), as the weights.
uint64_t sampleableWithMerges(const MisPath& path, TechniqueKind formedBy, MergeSite site = MergeSite::Every);

}  // namespace pathlab
