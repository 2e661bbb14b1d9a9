// Tests of the loader's bounds on what a small file can make it build: the triangle limit,
// counted over the node tree before anything is built, and the default scene index.
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "tests/scene/gltf_load_guard.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

// A mesh of `triangles` triangles (all the same three vertices through an index buffer, so the
// file stays small) instanced by `instances` root nodes.
TestGltf instancedScene(size_t triangles, size_t instances) {
  TestGltf g;
  std::vector<uint16_t> indices;
  // Distinct triangles over a small fan, so none is zero-area.
  std::vector<Vec3> positions = {{0, 0, 0}};
  for (int k = 0; k < 64; ++k) positions.emplace_back(std::cos(k * 0.09f), std::sin(k * 0.09f), 0.f);
  for (size_t t = 0; t < triangles; ++t) {
    const uint16_t a = uint16_t(1 + t % 63);
    for (uint16_t i : {uint16_t(0), a, uint16_t(a + 1)}) indices.push_back(i);
  }
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(positions), g.indices(indices))}, "block");
  for (size_t n = 0; n < instances; ++n) {
    g.root(R"({"mesh":)" + str(mesh) + R"(,"translation":[)" + std::to_string(n % 100) + "," +
           std::to_string(n / 100) + ",0]}");
  }
  return g;
}

TEST(GltfInstancing, AnInstancingBombIsRefusedBeforeAnythingIsBuilt) {
  // 10,000 nodes x 10,000 triangles: 100 M triangles from a file of a few hundred kB.
  const std::string path = instancedScene(10000, 10000).write("bomb.gltf");
  EXPECT_LT(fs::file_size(path), 2'000'000u);
  // A generous deadline: expanding it would take minutes and gigabytes, refusing it a moment.
  const GuardedLoad r = loadWithDeadline(path, LoadOptions{}, 60);
  ASSERT_TRUE(r.finished) << "the load did not finish (hung or crashed)";
  ASSERT_FALSE(r.loaded);
  EXPECT_EQ(r.message.rfind(path + ": ", 0), 0u) << r.message;
  EXPECT_NE(r.message.find("instances at least 50010000 triangles"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("more than the limit of 50000000 triangles"), std::string::npos)
      << r.message;
}

TEST(GltfInstancing, SharedSubtreesAreRefusedNotMultiplied) {
  // glTF's node hierarchy is a set of strict trees: ten levels of ten children each naming the
  // next level's nodes would be 10^10 instances if it were expanded, and is refused as a node
  // with two parents instead.
  TestGltf g;
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(kTriangle))});
  int level = g.node(R"({"mesh":)" + str(mesh) + "}");
  for (int depth = 0; depth < 10; ++depth) {
    std::string children;
    for (int c = 0; c < 10; ++c) children += (c ? "," : "") + str(level);
    level = g.node(R"({"children":[)" + children + "]}");
  }
  g.roots.push_back(level);
  const std::string path = g.write("shared-subtrees.gltf");
  const GuardedLoad r = loadWithDeadline(path, LoadOptions{}, 60);
  ASSERT_TRUE(r.finished) << "the load did not finish (hung or crashed)";
  EXPECT_NE(r.message.find("is reached twice"), std::string::npos) << r.message;
}

TEST(GltfInstancing, TheLimitIsAnOption) {
  // 200 instances of 1,000 triangles.
  const std::string path = instancedScene(1000, 200).write("moderate.gltf");
  LoadOptions low;
  low.maxTriangles = 100'000;
  const std::string message = [&] {
    try {
      loadGltf(path, low);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("loaded");
  }();
  EXPECT_NE(message.find("instances at least 101000 triangles"), std::string::npos) << message;
  EXPECT_NE(message.find("limit of 100000 triangles"), std::string::npos) << message;

  LoadOptions exact;
  exact.maxTriangles = 200'000;  // the limit itself is allowed
  EXPECT_EQ(totalTriangles(loadGltf(path, exact)), 200'000u);
  EXPECT_EQ(totalTriangles(loadGltf(path)), 200'000u);  // the default admits it
}

TEST(GltfInstancing, GeometryMemoryIsReported) {
  const Scene scene(loadGltf(instancedScene(1000, 100).write("memory.gltf")));
  // At least the world-space positions, normals and indices of 100,000 triangles.
  const size_t triangles = scene.triangleCount();
  EXPECT_EQ(triangles, 100'000u);
  EXPECT_GT(scene.geometryBytes(), triangles * 3 * sizeof(uint32_t));
  EXPECT_LT(scene.geometryBytes(), triangles * 1000);
}

TEST(GltfScenes, DefaultSceneIndexWithNoScenesIsRefused) {
  TestGltf g;
  g.withScenes = false;
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  TestGltf none = g;
  none.members.push_back(R"("scenes":[])");
  none.members.push_back(R"("scene":0)");
  EXPECT_NE(loadError(none.write("empty-scenes.gltf")).find("default scene 0 does not exist"),
            std::string::npos);
  TestGltf noArray = g;
  noArray.members.push_back(R"("scene":2)");
  EXPECT_NE(loadError(noArray.write("no-scenes.gltf")).find("default scene 2 does not exist"),
            std::string::npos);
  TestGltf negative = g;
  negative.withScenes = true;
  negative.members.push_back(R"("scene":-3)");
  EXPECT_NE(loadError(negative.write("negative-scene.gltf")).find("default scene -3 does not exist"),
            std::string::npos);
  // Without "scene" nor "scenes", every root node is rendered (the loader's documented choice).
  EXPECT_EQ(totalTriangles(loadGltf(g.write("no-scene-at-all.gltf"))), 1u);
}

}  // namespace
}  // namespace pathlab
