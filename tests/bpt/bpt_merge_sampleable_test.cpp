// sampleableWithMerges on hand-made paths: which connections and merges of a path's length could
// sample it (the technique maps' "cannot sample" with vertex merging), against closed-form
// reasoning about delta vertices (Veach 1997, sec. 10.3.5; a merge needs a non-delta surface
// vertex to merge at, Georgiev et al. 2012, sec. 4).
#include "core/bpt/merge_sampleable.h"

#include <gtest/gtest.h>

#include <vector>

namespace pathlab {
namespace {

PathVertex sampleableVertex(VertexType type, bool delta, int light = -1) {
  PathVertex v;
  v.type = type;
  v.isDelta = delta;
  v.light = light;
  return v;
}

// Bit of technique x in a mask over its length (Technique::slot()).
uint64_t bitOf(Technique x) { return uint64_t{1} << x.slot(); }

// x0 on an area light, x1 and x2 diffuse, x3 a mirror, x4 the pinhole camera (length 4), formed by
// the connection (2,3): (0,5), (1,4) and (2,3) can sample it, (3,2) and (4,1) cannot (x3 is
// delta); the merges at x1 and x2, M(2,4) and M(3,3), can, the one at the mirror, M(4,2), cannot.
TEST(MergeSampleable, ConnectionPathGetsTheMergesAtItsDiffuseVertices) {
  std::vector<PathVertex> light = {sampleableVertex(VertexType::Light, false, 0),
                                   sampleableVertex(VertexType::Surface, false)};
  std::vector<PathVertex> camera = {sampleableVertex(VertexType::Camera, false),
                                    sampleableVertex(VertexType::Surface, true),
                                    sampleableVertex(VertexType::Surface, false)};
  camera[0].isDeltaPosition = true;
  const MisPath path{light.data(), 2, camera.data(), 3, nullptr, nullptr};
  const uint64_t expected = bitOf({0, 5}) | bitOf({1, 4}) | bitOf({2, 3}) | bitOf(Technique::merge(2, 4)) |
                            bitOf(Technique::merge(3, 3));
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Connection), expected);
  // The connections' bits are sampleableTechniques' (which BPT alone uses).
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Connection) & 0x1f, sampleableTechniques(path));
}

// x0 a point light, x1 a mirror, x2 diffuse, x3 a mirror, x4 the camera, formed by the merge
// M(3,3) at x2 (its MisPath is that of C(3,2): x3 = z1 follows the merged vertex). Every edge has
// a delta end and s = 0 cannot hit a point: no connection can sample the path, only M(3,3). The
// edge x2 -- x3 was sampled by the camera walk, not connected: x3 stays delta.
TEST(MergeSampleable, OnlyTheMergeSamplesLightBetweenMirrors) {
  std::vector<PathVertex> light = {sampleableVertex(VertexType::Light, false, 0),
                                   sampleableVertex(VertexType::Surface, true),
                                   sampleableVertex(VertexType::Surface, false)};
  light[0].isDeltaPosition = true;
  std::vector<PathVertex> camera = {sampleableVertex(VertexType::Camera, false),
                                    sampleableVertex(VertexType::Surface, true)};
  camera[0].isDeltaPosition = true;
  const MisPath path{light.data(), 3, camera.data(), 2, nullptr, nullptr};
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Merge), bitOf(Technique::merge(3, 3)));
}

}  // namespace
}  // namespace pathlab
