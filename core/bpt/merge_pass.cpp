// MergePass::index: the mergeable light vertices and their grid.
#include "core/bpt/merge_pass.h"

#include "core/math/rng.h"
#include "core/merge/room.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cassert>

namespace pathlab {

const PathVertex& MergePass::vertex(uint32_t v) const {
  assert(v < vertexCount());
  // The last item starting at or before v (empty items share their start with the next one).
  const size_t item = static_cast<size_t>(std::upper_bound(itemStart.begin(), itemStart.end() - 1, v) - itemStart.begin()) - 1;
  return walkItems[item].vertices[v - itemStart[item]];
}

void MergePass::index(float r, double keepNonCaustic, uint64_t keepKey) {
  radius = r;
  const float keep = static_cast<float>(keepNonCaustic);
  nonCaustic = static_cast<double>(keep);  // the weights use the very probability the filter does
  // The filter in parallel, its output in vertex order: each work item counts its mergeable
  // vertices, the items' offsets follow, then each item writes its own.
  const size_t items = walkItems.size();
  auto isMergeable = [&](size_t item, uint32_t i) {
    const PathVertex& v = walkItems[item].vertices[i];
    const uint32_t global = itemStart[item] + i;
    if (global == pathStart[global] || v.type != VertexType::Surface || v.isDelta) return false;
    // A caustic vertex (its predecessor, in the same item, scattered by a delta lobe) is kept;
    // another with probability keep, by a uniform number hashed from the pass and the vertex.
    if (keep >= 1.f || walkItems[item].vertices[i - 1].isDelta) return true;
    const float u = static_cast<float>(mixBits(keepKey ^ mixBits(global)) >> 40) * 0x1p-24f;
    return u < keep;
  };
  std::vector<uint32_t> outStart(items + 1, 0);
  tbb::parallel_for(size_t{0}, items, [&](size_t item) {
    uint32_t n = 0;
    for (uint32_t i = 0, end = static_cast<uint32_t>(walkItems[item].vertices.size()); i < end; ++i)
      n += isMergeable(item, i) ? 1u : 0u;
    outStart[item + 1] = n;
  });
  for (size_t item = 0; item < items; ++item) outStart[item + 1] += outStart[item];
  resizeWithRoom(mergeable, outStart[items]);
  resizeWithRoom(mergeablePoints, mergeable.size());
  resizeWithRoom(mergeableVertex, mergeable.size());
  tbb::parallel_for(size_t{0}, items, [&](size_t item) {
    uint32_t out = outStart[item];
    const std::vector<PathVertex>& vertices = walkItems[item].vertices;
    for (uint32_t i = 0, end = static_cast<uint32_t>(vertices.size()); i < end; ++i)
      if (isMergeable(item, i)) {
        mergeable[out] = itemStart[item] + i;
        mergeableVertex[out] = &vertices[i];
        mergeablePoints[out++] = vertices[i].p;
      }
  });
  grid.build(mergeablePoints, r);
  resizeWithRoom(records, mergeable.size());
  tbb::parallel_for(size_t{0}, records.size(), [&](size_t j) {
    MergeRecord& record = records[j];
    const uint32_t point = grid.pointOfSlot(static_cast<uint32_t>(j));
    record.vertex = mergeable[point];
    const PathVertex& v = *mergeableVertex[point];
    record.wo = v.wo;
    // Kept with probability keep: the survivor stands for 1 / keep of them (unbiased for the
    // merges of the pass that keeps every vertex).
    const bool caustic = (&v - 1)->isDelta;
    record.beta = caustic || keep >= 1.f ? v.beta : v.beta / keep;
    record.s = static_cast<int>(record.vertex - pathStart[record.vertex]) + 1;
  });
}

}  // namespace pathlab
