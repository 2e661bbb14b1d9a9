// Tests of normal maps: the tangent frame (from the file or generated from uv derivatives), the
// handedness convention of glTF (the map's +y is -dp/dv), normalTexture.scale, and the mapped
// normal reaching SurfaceHit::ns.
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "core/scene/tangents.h"
#include "tests/scene/gltf_surface_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

// One triangle in the xy plane (normal +z, uv (0,0) (1,0) (0,1): dp/du = +x, dp/dv = +y) whose
// material's normal map is the single texel `rgb`; with TANGENT `tangent` when given.
Scene normalMapped(const std::string& name, std::vector<uint16_t> rgb, const std::string& scale = "1",
                   const Vec4* tangent = nullptr) {
  TestGltf g;
  addImageTexture(g, 1, 1, 3, rgb);
  g.add("materials", R"({"normalTexture":{"index":0,"scale":)" + scale + "}}");
  const std::vector<Vec2> uv = {{0, 0}, {1, 0}, {0, 1}};
  std::string attributes = R"("POSITION":)" + str(g.vec3(kTriangle)) + R"(,"NORMAL":)" +
                           str(g.vec3(kUp)) + R"(,"TEXCOORD_0":)" + str(g.vec2(uv));
  if (tangent) {
    const std::vector<Vec4> t(3, *tangent);
    attributes += R"(,"TANGENT":)" +
                  str(g.accessor(g.view(t.data(), t.size() * sizeof(Vec4)), 5126, 3, "VEC4"));
  }
  g.root(R"({"mesh":)" + str(g.mesh({R"({"attributes":{)" + attributes + R"(},"material":0})"})) + "}");
  return Scene(loadGltf(g.write(name)));
}

Vec3 shadingNormal(const Scene& scene) {
  const auto hit = scene.intersect(Ray{Vec3(0.25f, 0.25f, 1.f), Vec3(0.f, 0.f, -1.f)});
  EXPECT_TRUE(hit.has_value());
  return hit ? hit->ns : Vec3(0.f);
}

// Texel 218 -> 2 * 218 / 255 - 1 = 0.7098, 128 -> 0.0039: tilted 45 degrees.
constexpr float kTilt = 0.70980392f, kFlat = 0.00392157f;

Vec3 unit(Vec3 v) { return glm::normalize(v); }

TEST(GltfNormalMap, RedTiltsTowardTheTangent) {
  const Scene scene = normalMapped("normal-red.gltf", {218, 128, 218});
  EXPECT_TRUE(scene.warnings().empty()) << ::testing::PrintToString(scene.warnings());
  ASSERT_EQ(scene.meshes()[0].tangents.size(), scene.meshes()[0].positions.size());
  expectNear(shadingNormal(scene), unit(Vec3(kTilt, -kFlat, kTilt)));
}

TEST(GltfNormalMap, GreenTiltsAgainstDpDvWhenGenerated) {
  // glTF's v runs down the image, so the map's +y is -dp/dv = -y here (generated handedness -1).
  const Scene scene = normalMapped("normal-green.gltf", {128, 218, 218});
  expectNear(shadingNormal(scene), unit(Vec3(kFlat, -kTilt, kTilt)));
  EXPECT_EQ(scene.meshes()[0].tangents[0].w, -1.f);
}

TEST(GltfNormalMap, FileTangentsAndTheirHandednessAreUsed) {
  const Vec4 tangent(0.f, 1.f, 0.f, 1.f);  // tangent +y; bitangent = cross(z, y) = -x
  const Scene scene = normalMapped("normal-tangent.gltf", {218, 218, 218}, "1", &tangent);
  expectNear(shadingNormal(scene), unit(Vec3(-kTilt, kTilt, kTilt)));
}

TEST(GltfNormalMap, ScaleScalesTheTilt) {
  const Scene scene = normalMapped("normal-scale.gltf", {218, 128, 218}, "0.5");
  expectNear(shadingNormal(scene), unit(Vec3(0.5f * kTilt, -0.5f * kFlat, kTilt)));
}

TEST(GltfNormalMap, GeneratedTangentsFollowDpDuOnASkewedMapping) {
  // uv (0,0), (2,0), (1,1) on (0,0,0), (1,0,0), (0,1,0): u = 2x + ... solve: dp/du = (0.5, 0, 0),
  // dp/dv = (-0.5, 1, 0); the tangent is dp/du made unit, the handedness from -dp/dv.
  const std::vector<Vec3> p = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::vector<Vec3> n(3, Vec3(0, 0, 1));
  const std::vector<Vec2> uv = {{0, 0}, {2, 0}, {1, 1}};
  const std::vector<Vec4> t = generateTangents(p, n, uv, {0, 1, 2});
  for (const Vec4& v : t) {
    expectNear(Vec3(v), Vec3(1, 0, 0));
    EXPECT_EQ(v.w, -1.f);
  }
  // Without uvs: some unit tangent perpendicular to the normal.
  for (const Vec4& v : generateTangents(p, n, {}, {0, 1, 2})) {
    EXPECT_NEAR(glm::length(Vec3(v)), 1.f, 1e-6f);
    EXPECT_NEAR(glm::dot(Vec3(v), n[0]), 0.f, 1e-6f);
  }
}

}  // namespace
}  // namespace pathlab
