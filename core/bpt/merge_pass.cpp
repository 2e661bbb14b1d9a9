// MergePass::index: the mergeable light vertices and their grid.
#include "core/bpt/merge_pass.h"

#include <tbb/parallel_for.h>

namespace pathlab {

void MergePass::index(float r) {
  radius = r;
  mergeable.clear();
  for (uint32_t i = 0; i < vertices.size(); ++i) {
    const PathVertex& v = vertices[i];
    if (i != pathStart[i] && v.type == VertexType::Surface && !v.isDelta) mergeable.push_back(i);
  }
  std::vector<Vec3> points(mergeable.size());
  tbb::parallel_for(size_t{0}, points.size(), [&](size_t i) { points[i] = vertices[mergeable[i]].p; });
  grid.build(points, r);
}

}  // namespace pathlab
