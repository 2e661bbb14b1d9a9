// Tests of glTF alpha modes: MASK cut-outs and BLEND's stochastic transparency, for traced rays
// and for shadow rays (Scene::visible), from the loader to the Embree filters.
#include "core/scene/alpha_test.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "tests/scene/gltf_surface_scenes.h"
#include "core/math/rng.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

using namespace gltf_test;

// A floor (y = 0, 4 x 4, opaque) under an occluder quad at y = 1 (2 x 2) of material `occluder`.
// The occluder's texture is 2 x 1 RGBA NEAREST: alpha 0 on its -x half, 1 on its +x half.
std::string occluderScene(const std::string& name, const std::string& occluderMaterial) {
  TestGltf g;
  g.add("samplers", R"({"magFilter":9728,"wrapS":33071,"wrapT":33071})");
  addImageTexture(g, 2, 1, 4, {255, 255, 255, 0, 255, 255, 255, 255}, 0);
  g.add("materials", R"({"name":"floor","pbrMetallicRoughness":{"metallicFactor":0}})");
  g.add("materials", occluderMaterial);
  addQuad(g, Vec3(0.f), Vec3(0, 0, 2), Vec3(2, 0, 0), 0);                  // normal +y
  addQuad(g, Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(0, 0, -1), 1);             // normal +y, u along +x
  return g.write(name);
}

// Which mesh a ray straight down at (x, z) hits first: 0 floor, 1 occluder, -1 nothing.
int firstHit(const Scene& scene, float x, float z) {
  const auto hit = scene.intersect(Ray{Vec3(x, 3.f, z), Vec3(0.f, -1.f, 0.f)});
  return hit ? int(hit->meshId) : -1;
}

bool lit(const Scene& scene, float x, float z) {
  return scene.visible(Vec3(x, 0.f, z), Vec3(0, 1, 0), Vec3(0.f), Vec3(x, 3.f, z), Vec3(0.f), Vec3(0.f));
}

TEST(GltfAlpha, LoaderReadsModesAndCutoff) {
  TestGltf g;
  g.add("materials", R"({"alphaMode":"MASK","alphaCutoff":0.25})");
  g.add("materials", R"({"alphaMode":"BLEND"})");
  g.add("materials", R"({"alphaMode":"OPAQUE"})");
  for (int m = 0; m < 3; ++m) addTexturedTriangle(g, m);
  const SceneDesc d = loadGltf(g.write("alpha-modes.gltf"));
  EXPECT_TRUE(d.warnings.empty()) << ::testing::PrintToString(d.warnings);
  EXPECT_EQ(d.materials[0].alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(d.materials[0].alphaCutoff, 0.25f);
  EXPECT_EQ(d.materials[1].alphaMode, AlphaMode::Blend);
  EXPECT_EQ(d.materials[2].alphaMode, AlphaMode::Opaque);
  EXPECT_FALSE(d.materials[2].hasAlphaTest());
}

TEST(GltfAlpha, MaskCutsOutForTracedAndShadowRays) {
  const Scene scene(loadGltf(occluderScene(
      "alpha-mask.gltf",
      R"({"alphaMode":"MASK","pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})")));
  EXPECT_EQ(firstHit(scene, -0.5f, 0.f), 0);  // through the cut-out half onto the floor
  EXPECT_EQ(firstHit(scene, 0.5f, 0.f), 1);   // the opaque half
  EXPECT_TRUE(lit(scene, -0.5f, 0.2f));
  EXPECT_FALSE(lit(scene, 0.5f, 0.2f));
  EXPECT_TRUE(lit(scene, 1.5f, 0.f));  // beside the occluder
}

TEST(GltfAlpha, OpaqueMaterialsIgnoreAlpha) {
  const Scene scene(loadGltf(occluderScene(
      "alpha-opaque.gltf", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})")));
  EXPECT_EQ(firstHit(scene, -0.5f, 0.f), 1);
  EXPECT_FALSE(lit(scene, -0.5f, 0.2f));
}

// BLEND with alpha 0.3 (factor) meets a ray with probability 0.3, traced and shadow rays alike:
// binomial z-tests over independent rays.
TEST(GltfAlpha, BlendIsMetWithProbabilityAlpha) {
  const Scene scene(loadGltf(occluderScene(
      "alpha-blend.gltf",
      R"({"alphaMode":"BLEND","pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.3]}})")));
  constexpr int kRays = 20000;
  int hits = 0, blocked = 0;
  Pcg32 rng(7, 1);
  for (int i = 0; i < kRays; ++i) {
    const Vec2 u = rng.next2D();
    const float x = 1.8f * u.x - 0.9f, z = 1.8f * u.y - 0.9f;
    hits += firstHit(scene, x, z) == 1;
    blocked += !lit(scene, x, z);
  }
  const double p = 0.3, se = std::sqrt(p * (1 - p) / kRays);
  EXPECT_LT(std::abs(double(hits) / kRays - p), 4.5 * se) << hits;
  EXPECT_LT(std::abs(double(blocked) / kRays - p), 4.5 * se) << blocked;
  // The same ray gets the same answer (Embree may ask a filter twice).
  EXPECT_EQ(firstHit(scene, 0.123f, 0.456f), firstHit(scene, 0.123f, 0.456f));
}

TEST(GltfAlpha, AlphaMultipliesFactorTextureAndVertexColour) {
  Material m;
  m.alphaMode = AlphaMode::Mask;
  m.baseColorFactor = Vec4(1.f, 1.f, 1.f, 0.5f);
  TriangleMesh mesh;
  mesh.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.indices = {0, 1, 2};
  mesh.colors = {Vec4(1.f, 1.f, 1.f, 1.f), Vec4(1.f, 1.f, 1.f, 0.f), Vec4(1.f, 1.f, 1.f, 1.f)};
  const std::vector<Texture> none;
  const AlphaGeometry g{&mesh, &m, &none};
  // At vertex 0: alpha 0.5 * 1 = 0.5 >= cutoff 0.5; towards vertex 1 it falls below.
  EXPECT_TRUE(alphaCovers(g, 0, 0.f, 0.f, 0.f));
  EXPECT_FALSE(alphaCovers(g, 0, 0.2f, 0.f, 0.f));
  m.alphaCutoff = 0.3f;
  EXPECT_TRUE(alphaCovers(g, 0, 0.2f, 0.f, 0.f));  // 0.5 * 0.8 = 0.4
}

}  // namespace
}  // namespace pathlab
