// Tests of the glTF loader's geometry: node transforms and the hierarchy, the default scene,
// indexed, interleaved, instanced, degenerate and quantized primitives, and GLB against .gltf.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

// ---- transforms and the node hierarchy -------------------------------------------------------

TEST(GltfTransform, TrsAndMatrixGiveTheSameWorldPositions) {
  // T (1,2,3) * R (90 degrees about +y: x -> -z, z -> x) * S (2): the same map both ways.
  const std::string trs = oneTriangle(
      "trs.gltf",
      R"("translation":[1,2,3],"rotation":[0,0.70710678,0,0.70710678],"scale":[2,2,2])");
  const std::string matrix =
      oneTriangle("matrix.gltf", R"("matrix":[0,0,-2,0, 0,2,0,0, 2,0,0,0, 1,2,3,1])");
  for (const std::string& path : {trs, matrix}) {
    SCOPED_TRACE(path);
    const SceneDesc d = loadGltf(path);
    ASSERT_EQ(d.meshes.size(), 1u);
    const TriangleMesh& m = d.meshes[0];
    ASSERT_EQ(m.triangleCount(), 1u);
    expectNear(m.positions[m.indices[0]], {1, 2, 3});
    expectNear(m.positions[m.indices[1]], {1, 2, 1});
    expectNear(m.positions[m.indices[2]], {1, 4, 3});
    for (const Vec3& n : m.normals) expectNear(n, {1, 0, 0});
    expectConsistentWinding(m);
  }
}

TEST(GltfTransform, NestedNodesComposeParentFirst) {
  TestGltf g;
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(kTriangle), -1, g.vec3(kUp))});
  const int grandchild = g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[0,1,0]})");
  const int child = g.node(R"({"mesh":)" + str(mesh) + R"(,"scale":[3,3,3],"children":[)" +
                           str(grandchild) + "]}");
  g.root(R"({"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 10,0,0,1],"children":[)" + str(child) + "]}");
  const SceneDesc d = loadGltf(g.write("nested.gltf"));
  ASSERT_EQ(d.meshes.size(), 2u);  // one TriangleMesh per instance, in document order
  // child: T(10) S(3); grandchild: T(10) S(3) T(0,1,0).
  expectNear(d.meshes[0].positions[1], {13, 0, 0});
  expectNear(d.meshes[1].positions[0], {10, 3, 0});
  expectNear(d.meshes[1].positions[1], {13, 3, 0});
  expectNear(d.meshes[1].positions[2], {10, 6, 0});
}

TEST(GltfTransform, NegativeScaleFlipsWindingToAgreeWithNormals) {
  // A tilted normal so the mirrored normal differs from the unmirrored one.
  const Vec3 n = glm::normalize(Vec3(1, 1, 1));
  const std::vector<Vec3> tri = {{0, 0, 0}, {1, -1, 0}, {0, 1, -1}};  // CCW about n
  for (const char* scale : {"[-1,1,1]", "[1,-2,1]", "[-1,-1,-1]", "[1,1,1]"}) {
    SCOPED_TRACE(scale);
    for (bool authored : {true, false}) {
      TestGltf g;
      const int nrm = authored ? g.vec3({n, n, n}) : -1;
      const int mesh = g.mesh({TestGltf::primitive(g.vec3(tri), -1, nrm)});
      g.root(R"({"mesh":)" + str(mesh) + R"(,"scale":)" + scale + "}");
      const SceneDesc d = loadGltf(g.write("mirror.gltf"));
      ASSERT_EQ(d.meshes.size(), 1u);
      expectConsistentWinding(d.meshes[0]);
    }
  }
  // The mirrored authored normal is the inverse transpose: (-1,1,1)/sqrt(3) for scale (-1,1,1).
  TestGltf g;
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(tri), -1, g.vec3({n, n, n}))});
  g.root(R"({"mesh":)" + str(mesh) + R"(,"scale":[-1,1,1]})");
  const SceneDesc d = loadGltf(g.write("mirror.gltf"));
  expectNear(d.meshes[0].normals[0], glm::normalize(Vec3(-1, 1, 1)));
}

TEST(GltfScene, DefaultSceneIsTheOneNamedBySceneElseSceneZero) {
  auto build = [](const std::string& sceneMember) {
    TestGltf g;
    const int mesh = g.mesh({TestGltf::primitive(g.vec3(kTriangle))});
    const int a = g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[100,0,0]})");
    const int b = g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[200,0,0]})");
    g.scene({a});
    g.scene({b});
    if (!sceneMember.empty()) g.members.push_back(sceneMember);
    return loadGltf(g.write("scenes.gltf"));
  };
  const SceneDesc second = build(R"("scene":1)");
  ASSERT_EQ(second.meshes.size(), 1u);
  EXPECT_FLOAT_EQ(second.meshes[0].positions[0].x, 200.f);
  const SceneDesc first = build("");
  ASSERT_EQ(first.meshes.size(), 1u);
  EXPECT_FLOAT_EQ(first.meshes[0].positions[0].x, 100.f);
}

TEST(GltfScene, WithoutScenesEveryRootNodeIsLoadedOnce) {
  TestGltf g;
  g.withScenes = false;
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(kTriangle))});
  const int child = g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[0,0,5]})");
  g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[100,0,0],"children":[)" + str(child) +
         "]}");
  g.node(R"({"mesh":)" + str(mesh) + R"(,"translation":[200,0,0]})");
  const SceneDesc d = loadGltf(g.write("noscenes.gltf"));
  ASSERT_EQ(d.meshes.size(), 3u);
  std::vector<Vec3> origins;
  for (const TriangleMesh& m : d.meshes) origins.push_back(m.positions[0]);
  expectNear(origins[0], {100, 0, 0});
  expectNear(origins[1], {100, 0, 5});
  expectNear(origins[2], {200, 0, 0});
}

// ---- geometry ------------------------------------------------------------------------------

TEST(GltfGeometry, IndexedAndNonIndexedPrimitivesAgree) {
  const std::vector<Vec3> quad = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<uint32_t> idx = {0, 1, 2, 0, 2, 3};
  std::vector<Vec3> soup;
  for (uint32_t i : idx) soup.push_back(quad[i]);

  TestGltf plain;
  plain.root(R"({"mesh":)" + str(plain.mesh({TestGltf::primitive(plain.vec3(soup))})) + "}");
  const std::vector<Vec3> expected = corners(loadGltf(plain.write("soup.gltf")));
  ASSERT_EQ(expected.size(), 6u);

  for (int bytes : {1, 2, 4}) {
    SCOPED_TRACE(bytes);
    TestGltf g;
    int indices = -1;
    if (bytes == 1) indices = g.indices(std::vector<uint8_t>(idx.begin(), idx.end()));
    if (bytes == 2) indices = g.indices(std::vector<uint16_t>(idx.begin(), idx.end()));
    if (bytes == 4) indices = g.indices(idx);
    g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(quad), indices)})) + "}");
    const std::vector<Vec3> got = corners(loadGltf(g.write("indexed.gltf")));
    ASSERT_EQ(got.size(), expected.size());
    for (size_t i = 0; i < got.size(); ++i) expectNear(got[i], expected[i], 0.f);
  }
}

TEST(GltfGeometry, MissingNormalsBecomeFlatFaceNormals) {
  // Two triangles folded along the x axis, under a non-uniform scale: flat normals (one vertex per
  // corner) equal to the world-space face normal (glTF 2.0 spec, sec. 3.7.2.1).
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  TestGltf g;
  const int indices = g.indices(std::vector<uint16_t>{0, 1, 2, 0, 3, 1});
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(positions), indices)})) +
         R"(,"scale":[1,2,3]})");
  const SceneDesc d = loadGltf(g.write("nonormals.gltf"));
  ASSERT_EQ(d.meshes.size(), 1u);
  const TriangleMesh& m = d.meshes[0];
  EXPECT_EQ(m.positions.size(), 6u);
  ASSERT_EQ(m.triangleCount(), 2u);
  for (size_t t = 0; t < 2; ++t) {
    const uint32_t* i = &m.indices[3 * t];
    const Vec3 face = glm::normalize(
        glm::cross(m.positions[i[1]] - m.positions[i[0]], m.positions[i[2]] - m.positions[i[0]]));
    for (int k = 0; k < 3; ++k) expectNear(m.normals[i[k]], face);
  }
  expectNear(m.normals[m.indices[0]], {0, 0, 1});
  expectNear(m.normals[m.indices[3]], {0, 1, 0});
}

TEST(GltfGeometry, ByteStrideOffsetsAndNormalizedTexcoords) {
  // Interleaved position + normal (stride 24, normals at byteOffset 12) and unsigned-short
  // normalized uvs at a bufferView offset.
  TestGltf g;
  std::vector<float> interleaved;
  for (int v = 0; v < 3; ++v) {
    for (int k = 0; k < 3; ++k) interleaved.push_back(kTriangle[size_t(v)][k]);
    for (int k = 0; k < 3; ++k) interleaved.push_back(kUp[size_t(v)][k]);
  }
  const int view = g.view(interleaved.data(), interleaved.size() * sizeof(float), 24);
  const int pos = g.accessor(view, 5126, 3, "VEC3", 0);
  const int nrm = g.accessor(view, 5126, 3, "VEC3", 12);
  const std::vector<uint16_t> uv16 = {0, 65535, 65535, 0, 32768, 65535};
  const int uv = g.accessor(g.view(uv16.data(), uv16.size() * 2), 5123, 3, "VEC2", 0, true);
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(pos, -1, nrm, uv)})) + "}");
  const SceneDesc d = loadGltf(g.write("interleaved.gltf"));
  ASSERT_EQ(d.meshes.size(), 1u);
  const TriangleMesh& m = d.meshes[0];
  for (int v = 0; v < 3; ++v) {
    expectNear(m.positions[size_t(v)], kTriangle[size_t(v)], 0.f);
    expectNear(m.normals[size_t(v)], {0, 0, 1}, 0.f);
  }
  ASSERT_EQ(m.uvs.size(), 3u);
  EXPECT_FLOAT_EQ(m.uvs[0].x, 0.f);
  EXPECT_FLOAT_EQ(m.uvs[0].y, 1.f);
  EXPECT_FLOAT_EQ(m.uvs[1].x, 1.f);
  EXPECT_NEAR(m.uvs[2].x, 32768.f / 65535.f, 1e-7f);
}

TEST(GltfGeometry, AnInstancedMeshGivesOneTriangleMeshPerPrimitiveInstance) {
  TestGltf g;
  const int pos = g.vec3(kTriangle);
  const int mesh = g.mesh({TestGltf::primitive(pos), TestGltf::primitive(pos)}, "twoPrims");
  g.root(R"({"mesh":)" + str(mesh) + "}");
  g.root(R"({"mesh":)" + str(mesh) + R"(,"translation":[0,0,1]})");
  const SceneDesc d = loadGltf(g.write("instanced.gltf"));
  ASSERT_EQ(d.meshes.size(), 4u);
  EXPECT_EQ(d.meshes[0].name, "twoPrims.0");
  EXPECT_EQ(d.meshes[1].name, "twoPrims.1");
  EXPECT_FLOAT_EQ(d.meshes[3].positions[0].z, 1.f);
}

TEST(GltfGeometry, PrimitivesSharingAVertexBufferKeepOnlyTheVerticesTheyUse) {
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 0, 0}, {6, 0, 0}, {5, 1, 0}};
  TestGltf g;
  const int pos = g.vec3(p);
  const int first = g.indices(std::vector<uint8_t>{0, 1, 2});
  const int second = g.indices(std::vector<uint8_t>{3, 4, 5});
  g.root(R"({"mesh":)" +
         str(g.mesh({TestGltf::primitive(pos, first), TestGltf::primitive(pos, second)})) + "}");
  const SceneDesc d = loadGltf(g.write("shared.gltf"));
  ASSERT_EQ(d.meshes.size(), 2u);
  ASSERT_EQ(d.meshes[1].positions.size(), 3u);
  expectNear(d.meshes[1].positions[d.meshes[1].indices[0]], {5, 0, 0}, 0.f);
}

TEST(GltfGeometry, NonTrianglePrimitivesAreSkippedWithAWarning) {
  TestGltf g;
  const int pos = g.vec3(kTriangle);
  g.root(R"({"mesh":)" +
         str(g.mesh({TestGltf::primitive(pos, -1, -1, -1, -1, 1), TestGltf::primitive(pos)})) +
         "}");
  const SceneDesc d = loadGltf(g.write("lines.gltf"));
  EXPECT_EQ(d.meshes.size(), 1u);
  EXPECT_TRUE(hasWarning(d, "LINES")) << ::testing::PrintToString(d.warnings);
}

TEST(GltfGeometry, ZeroAreaTrianglesAreDroppedWithOneWarningPerMesh) {
  // One good triangle, one with a repeated index, one collinear; the mesh instanced twice.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  TestGltf g;
  const int idx = g.indices(std::vector<uint8_t>{0, 1, 2, 0, 0, 2, 0, 1, 3});
  const int mesh = g.mesh({TestGltf::primitive(g.vec3(p), idx)}, "sliver");
  g.root(R"({"mesh":)" + str(mesh) + "}");
  g.root(R"({"mesh":)" + str(mesh) + R"(,"translation":[5,0,0]})");
  const SceneDesc d = loadGltf(g.write("degenerate.gltf"));
  EXPECT_EQ(totalTriangles(d), 2u);
  for (const TriangleMesh& m : d.meshes) EXPECT_EQ(m.positions.size(), 3u);  // vertex 3 dropped
  int count = 0;
  for (const std::string& w : d.warnings) count += w.find("zero-area") != std::string::npos;
  EXPECT_EQ(count, 1) << ::testing::PrintToString(d.warnings);
  EXPECT_TRUE(hasWarning(d, "'sliver': 2 zero-area triangles dropped"));
}

TEST(GltfGeometry, QuantizedPositionsAreAccepted) {
  // KHR_mesh_quantization: unnormalized signed-short positions.
  TestGltf g;
  const std::vector<int16_t> p = {0, 0, 0, 2, 0, 0, 0, 3, 0};
  const int pos = g.accessor(g.view(p.data(), p.size() * 2), 5122, 3, "VEC3");
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(pos)})) + "}");
  g.members.push_back(R"("extensionsUsed":["KHR_mesh_quantization"])");
  g.members.push_back(R"("extensionsRequired":["KHR_mesh_quantization"])");
  const SceneDesc d = loadGltf(g.write("quantized.gltf"));
  ASSERT_EQ(d.meshes.size(), 1u);
  expectNear(d.meshes[0].positions[1], {2, 0, 0}, 0.f);
  expectNear(d.meshes[0].positions[2], {0, 3, 0}, 0.f);
  EXPECT_TRUE(d.warnings.empty()) << ::testing::PrintToString(d.warnings);
}

// ---- binary glTF ---------------------------------------------------------------------------

TEST(GltfBinary, GlbLoadsLikeTheEquivalentGltf) {
  TestGltf g;
  const int idx = g.indices(std::vector<uint16_t>{0, 1, 2});
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle), idx, g.vec3(kUp))})) +
         R"(,"translation":[0,0,7]})");
  const std::vector<Vec3> text = corners(loadGltf(g.write("same.gltf")));
  const std::vector<Vec3> binary = corners(loadGltf(writeFile("same.glb", g.glb())));
  ASSERT_EQ(binary.size(), 3u);
  for (size_t i = 0; i < 3; ++i) expectNear(binary[i], text[i], 0.f);
  // The magic bytes decide, not the extension.
  EXPECT_EQ(corners(loadGltf(writeFile("binary-named.gltf", g.glb()))).size(), 3u);
}

}  // namespace
}  // namespace pathlab
