// The light subpaths of one pass kept for vertex merging (Georgiev et al. 2012, sec. 5): every
// pixel's light subpath, its vertices that can be merged indexed by a HashGrid, and the pass's
// radius. Built between passes by the render session, read by every camera sample of the pass.
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/merge/hash_grid.h"

#include <cmath>
#include <cstdint>
#include <vector>

namespace pathlab {

// The progressive radius (Knaus and Zwicker 2011; Georgiev et al. 2012 eq. 20): pass i (from 0)
// merges within r_i = r_1 (i + 1)^((alpha - 1) / 2), so the bias vanishes as passes add up while
// the variance of the running average still falls (0 < alpha < 1; alpha = 1 keeps r_1).
inline float mergeRadius(float firstRadius, float alpha, uint64_t pass) {
  return firstRadius * static_cast<float>(std::pow(static_cast<double>(pass) + 1.0, (static_cast<double>(alpha) - 1.0) / 2.0));
}

struct MergePass {
  std::vector<PathVertex> vertices;   // every light subpath of the pass, path after path
  std::vector<uint32_t> pathStart;    // per vertex: the index of its path's vertex 0
  std::vector<uint32_t> mergeable;    // the vertices a camera vertex may merge with (HashGrid point i)
  // Pixel (x, y)'s light subpath: vertices[pixelPathStart[p] ..] for pixelPathCount[p] vertices,
  // p = y * width + x; its camera sample connects to it instead of walking it again.
  int width = 0;
  std::vector<uint32_t> pixelPathStart, pixelPathCount;
  // The MIS partial sums of every stored vertex (BidirTracer::lightSubpathSums): misSum[v] for
  // vertex v, i-th of its path, is SubpathMisSums::sum[i] (its prefix before it), misShortestEdge2[v]
  // the shortest edge up to it. Empty when the weights are explicit.
  std::vector<double> misSum;
  std::vector<float> misShortestEdge2;
  HashGrid grid;
  float radius = 0.f;
  uint64_t lightSubpaths = 0;  // N
  // eta = pi r^2 N, the merges' factor in every MIS weight (merge_mis.h), and 1 / (pi r^2 N), the
  // density estimate's normalisation of a merge's contribution (Georgiev et al. eq. 11).
  double eta() const { return 3.14159265358979323846 * static_cast<double>(radius) * radius * static_cast<double>(lightSubpaths); }
  double normalisation() const { return 1.0 / eta(); }

  // Keeps, of `vertices`, those that can be merged: on a surface, not the light origin (index 0 in
  // its path), not scattered by a delta lobe; then builds the grid over them with `radius`.
  void index(float radius);
};

}  // namespace pathlab
