// The light subpaths of one pass kept for vertex merging (Georgiev et al. 2012, sec. 5): every
// pixel's light subpath, its vertices that can be merged indexed by a HashGrid, and the pass's
// radius. Built between passes by the render session, read by every camera sample of the pass.
#pragma once

#include "core/bpt/mis_partial_sums.h"
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

// A mergeable light vertex as a merge reads it: its direction and throughput for the
// contribution, its MIS terms for the O(1) weight (mergeLightTerms), where it lies in `vertices`
// for everything else (the explicit weights, the inspector). Kept in the grid's slot order, so a
// query reads the records of a bucket one after another rather than a vertex, its path's start and
// its sums scattered over a store of a million vertices.
struct MergeRecord {
  Vec3 wo{0.f};
  Spectrum beta{0.f};
  uint32_t vertex = 0;  // index in MergePass::vertices
  int s = 0;            // the light vertex is y(s-1): vertex - (s - 1) is its path's x0
  MergeLightTerms mis;  // filled when the weights come from the partial sums
};

struct MergePass {
  // Every light subpath of the pass, where the walks wrote them: work item i's paths, one after
  // another, in walkItems[i].vertices. A vertex's index in the pass (MergeRecord::vertex,
  // pixelPathStart) counts through the items in order, itemStart[i] being item i's first; a path
  // never spans two items. The store is not joined into one array: that kept every vertex twice
  // (150 bytes each, about 1.5 KB a pixel, 3 GB at 1920 x 1080).
  struct WalkItem {
    std::vector<PathVertex> vertices;
    std::vector<uint32_t> pixels;                  // y * width + x, their paths in order
    std::vector<uint32_t> pixelStart, pixelCount;  // within the item
  };
  std::vector<WalkItem> walkItems;  // kept from pass to pass: a pass does not allocate them again
  std::vector<uint32_t> itemStart;  // walkItems.size() + 1 entries, the last the pass's vertex count
  std::vector<uint32_t> pathStart;  // per vertex: the index of its path's vertex 0
  std::vector<uint32_t> mergeable;  // the vertices a camera vertex may merge with (HashGrid point i)
  // Pixel (x, y)'s light subpath: pixelPathCount[p] vertices from index pixelPathStart[p], at
  // pixelPath[p], p = y * width + x; its camera sample connects to it instead of walking it again.
  int width = 0;
  std::vector<uint32_t> pixelPathStart, pixelPathCount;
  std::vector<const PathVertex*> pixelPath;
  // The MIS partial sums of every stored vertex (BidirTracer::lightSubpathSums): misSum[v] for
  // vertex v, i-th of its path, is SubpathMisSums::sum[i] (its prefix before it), misShortestEdge2[v]
  // the shortest edge up to it. Empty when the weights are explicit.
  std::vector<double> misSum;
  std::vector<float> misShortestEdge2;
  HashGrid grid;
  std::vector<MergeRecord> records;  // per grid slot (HashGrid::querySlots)
  float radius = 0.f;
  // The probability of keeping a mergeable light vertex that the light walk did not reach by a
  // delta bounce (mergeKeep; the caustic ones are always kept): every merge weight carries it.
  double nonCaustic = 1.0;
  uint64_t lightSubpaths = 0;  // N
  // eta = pi r^2 N, the merges' factor in every MIS weight (merge_mis.h), and 1 / (pi r^2 N), the
  // density estimate's normalisation of a merge's contribution (Georgiev et al. eq. 11).
  double eta() const { return 3.14159265358979323846 * static_cast<double>(radius) * radius * static_cast<double>(lightSubpaths); }
  double normalisation() const { return 1.0 / eta(); }

  size_t vertexCount() const { return itemStart.empty() ? 0 : itemStart.back(); }
  // Vertex v of the pass; the vertices of its path follow it in memory. A search over the items:
  // for the explicit weights and the inspector, not for the O(1) merge loop.
  const PathVertex& vertex(uint32_t v) const;
  // Index's scratch: the grid's points, and where each mergeable vertex lies.
  std::vector<Vec3> mergeablePoints;
  std::vector<const PathVertex*> mergeableVertex;

  // Keeps, of the stored vertices, those that can be merged: on a surface, not the light origin
  // (index 0 in its path), not scattered by a delta lobe; of these the non-caustic ones with
  // probability `nonCaustic` (their records' throughput divided by it), decided by a hash of
  // `keepKey` (a function of the seed and the pass, so any pass can be rebuilt) and the vertex's
  // index; then builds the grid over them with `radius` and their
  // records in its slot order (without `mis`: BidirTracer::prepareMergePass).
  void index(float radius, double nonCaustic = 1.0, uint64_t keepKey = 0);
};

}  // namespace pathlab
