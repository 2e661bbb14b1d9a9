// MergePass::index: the mergeable light vertices and their grid.
#include "core/bpt/merge_pass.h"

#include "core/merge/room.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace pathlab {

void MergePass::index(float r) {
  radius = r;
  // The filter in parallel, its output in vertex order: each block counts its mergeable
  // vertices, the blocks' offsets follow, then each block writes its own.
  constexpr size_t kBlock = 16384;
  const size_t blocks = (vertices.size() + kBlock - 1) / kBlock;
  auto isMergeable = [&](uint32_t i) {
    const PathVertex& v = vertices[i];
    return i != pathStart[i] && v.type == VertexType::Surface && !v.isDelta;
  };
  std::vector<uint32_t> blockStart(blocks + 1, 0);
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    uint32_t n = 0;
    for (size_t i = b * kBlock, end = std::min(vertices.size(), i + kBlock); i < end; ++i)
      n += isMergeable(static_cast<uint32_t>(i)) ? 1u : 0u;
    blockStart[b + 1] = n;
  });
  for (size_t b = 0; b < blocks; ++b) blockStart[b + 1] += blockStart[b];
  resizeWithRoom(mergeable, blockStart[blocks]);
  resizeWithRoom(mergeablePoints, mergeable.size());
  tbb::parallel_for(size_t{0}, blocks, [&](size_t b) {
    uint32_t out = blockStart[b];
    for (size_t i = b * kBlock, end = std::min(vertices.size(), i + kBlock); i < end; ++i)
      if (isMergeable(static_cast<uint32_t>(i))) {
        mergeable[out] = static_cast<uint32_t>(i);
        mergeablePoints[out++] = vertices[i].p;
      }
  });
  grid.build(mergeablePoints, r);
  resizeWithRoom(records, mergeable.size());
  tbb::parallel_for(size_t{0}, records.size(), [&](size_t j) {
    MergeRecord& record = records[j];
    record.vertex = mergeable[grid.pointOfSlot(static_cast<uint32_t>(j))];
    const PathVertex& v = vertices[record.vertex];
    record.wo = v.wo;
    record.beta = v.beta;
    record.s = static_cast<int>(record.vertex - pathStart[record.vertex]) + 1;
  });
}

}  // namespace pathlab
