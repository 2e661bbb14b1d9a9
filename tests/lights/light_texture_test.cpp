// Textured area lights: a triangle's power is what its texels emit (the emissive texture
// integrated over its uv footprint), a triangle over black texels is no light, light choice
// follows the integrated powers, and the power agrees with the emission sampleLe produces.
#include "core/lights/light.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "tests/lights/light_test_support.h"
#include "tests/support/statistics.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using light_test::kTri;

// Two texels along u, clamped, bilinear: black for u <= 1/4, ramping to white at u = 3/4
// (what an sRGB emissive texture half black, half white decodes to).
Texture halfBlackTexture() {
  Texture t;
  t.width = 2;
  t.height = 1;
  t.texels = {Vec4(0.f, 0.f, 0.f, 1.f), Vec4(1.f)};
  t.wrapS = t.wrapT = WrapMode::ClampToEdge;
  return t;
}

float triangleArea(const std::array<Vec3, 3>& p) {
  return 0.5f * glm::length(glm::cross(p[1] - p[0], p[2] - p[0]));
}

Light texturedArea(const std::array<Vec3, 3>& p, std::array<Vec2, 3> uv, const Spectrum& L,
                   const Texture* tex, bool twoSided) {
  return Light::area(p[0], p[1], p[2], uv[0], uv[1], uv[2], L, tex, twoSided);
}

// Phi = pi A Le per emitting side (Lambertian emitter), Le = emission x the texels under it.
TEST(LightTexture, PowerIsWhatTheCoveredTexelsEmit) {
  const Texture tex = halfBlackTexture();
  const Spectrum L(3.f, 2.f, 1.f);
  const float area = triangleArea(kTri);
  const std::array<Vec2, 3> overBlack = {Vec2(0.f, 0.f), Vec2(0.25f, 0.f), Vec2(0.f, 1.f)};
  const std::array<Vec2, 3> overBright = {Vec2(0.75f, 0.f), Vec2(1.f, 0.f), Vec2(1.f, 1.f)};
  for (bool twoSided : {false, true}) {
    EXPECT_EQ(texturedArea(kTri, overBlack, L, &tex, twoSided).power(), Spectrum(0.f));
    const Spectrum expected = L * (kPi * area * (twoSided ? 2.f : 1.f));
    const Spectrum power = texturedArea(kTri, overBright, L, &tex, twoSided).power();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(power[c], expected[c], 1e-5f * expected[c]) << c;
  }
  // Across the ramp: the uv square's lower triangle (v <= u) has mean 35/48 (texture_integral_test).
  const Spectrum across = texturedArea(kTri, {Vec2(0.f), Vec2(1.f, 0.f), Vec2(1.f)}, L, &tex, false).power();
  EXPECT_NEAR(across.r, 35.f / 48.f * L.r * kPi * area, 1e-5f * L.r * kPi * area);
}

// The flux sampleLe's emitted rays carry (Le |cos| / (pdfPos pdfDir), averaged) is power(): the
// integrated texture, not the whole texture's average, is what the light's radiance integrates to.
TEST(LightTexture, PowerMatchesTheFluxSampleLeCarries) {
  const Texture tex = halfBlackTexture();
  const std::array<Vec2, 3> uv = {Vec2(0.1f, 0.f), Vec2(0.9f, 0.2f), Vec2(0.6f, 1.f)};
  for (bool twoSided : {false, true}) {
    const Light light = texturedArea(kTri, uv, Spectrum(2.f, 1.f, 4.f), &tex, twoSided);
    Pcg32 rng(51, 52);
    test::RunningStats flux;
    for (int k = 0; k < 200000; ++k) {
      const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
      ASSERT_GT(s.pdfPosA * s.pdfDirW, 0.f);
      // Le read where the ray starts: the uv sampleLe reports is that point's.
      ASSERT_EQ(s.Le, light.radiance(s.n, s.uv, s.ray.d));
      flux.add(double(luminance(s.Le)) * absDot(s.n, s.ray.d) / (double(s.pdfPosA) * s.pdfDirW));
    }
    const double expected = luminance(light.power());
    EXPECT_NEAR(flux.mean(), expected, 4.0 * flux.standardError()) << "two-sided " << twoSided;
    EXPECT_LT(flux.standardError(), 0.01 * expected);
  }
}

// A quad emitter over the half-black texture, split along its uv diagonal into triangles of mean
// 35/48 and 13/48, and a third triangle entirely over the black half: the third stays a surface
// but is no light, and the other two are chosen 35 : 13.
SceneDesc halfBlackEmitterScene() {
  SceneDesc d;
  d.path = "half-black-emitter";
  d.materials.push_back(test::lambertian(0.5f, Spectrum(4.f)));
  d.materials.back().emissiveTexture.texture = 0;
  d.textures.push_back(halfBlackTexture());
  // Facing -z; uv (0, 0) at the corner (-1, -1) where the texture is black.
  d.meshes.push_back(test::quad(Vec3(-1.f, -1.f, 0.f), Vec3(-1.f, 1.f, 0.f), Vec3(1.f, 1.f, 0.f), Vec3(1.f, -1.f, 0.f), 0));
  d.meshes[0].uvs = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  TriangleMesh dark;
  dark.positions = {Vec3(-1.f, -1.f, 1.f), Vec3(-1.f, 1.f, 1.f), Vec3(-0.8f, 1.f, 1.f)};
  dark.normals.assign(3, Vec3(0.f, 0.f, -1.f));
  dark.uvs = {{0.f, 0.f}, {0.f, 1.f}, {0.2f, 1.f}};
  dark.indices = {0, 1, 2};
  d.meshes.push_back(dark);
  return d;
}

TEST(LightTexture, BlackTrianglesAreNoLightsAndChoiceFollowsIntegratedPower) {
  const Scene scene(halfBlackEmitterScene());
  const LightSet& lights = scene.lights();
  ASSERT_EQ(lights.size(), 2u);
  EXPECT_EQ(lights.lightOfTriangle(1, 0), -1);
  // The dark triangle is still there to be hit.
  const auto hit = scene.intersect(Ray{Vec3(-0.95f, 0.5f, 3.f), Vec3(0.f, 0.f, -1.f)});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->meshId, 1u);
  EXPECT_EQ(hit->light, -1);
  // Triangle 0 of the quad has uvs (0,0) (0,1) (1,1): the side v >= u, mean 13/48; triangle 1
  // the side v <= u, mean 35/48. Equal areas, so their choice probabilities are 13/48 and 35/48.
  const int upper = lights.lightOfTriangle(0, 0), lower = lights.lightOfTriangle(0, 1);
  ASSERT_GE(upper, 0);
  ASSERT_GE(lower, 0);
  EXPECT_NEAR(lights.pmf(upper), 13.0 / 48.0, 1e-6);
  EXPECT_NEAR(lights.pmf(lower), 35.0 / 48.0, 1e-6);
  // And the sampler draws them so (z-test on the frequency).
  Pcg32 rng(53, 54);
  const int n = 100000;
  int lowerCount = 0;
  for (int k = 0; k < n; ++k) {
    float pmf = 0.f;
    const int i = lights.sample(rng.next1D(), &pmf);
    ASSERT_TRUE(i == upper || i == lower);
    ASSERT_EQ(pmf, lights.pmf(i));
    lowerCount += i == lower;
  }
  const double p = 35.0 / 48.0, se = std::sqrt(p * (1 - p) / n);
  EXPECT_NEAR(double(lowerCount) / n, p, 4 * se);
}

// Only black texels: nothing emits, so the scene is refused as having no light source.
TEST(LightTexture, AllBlackEmitterIsNoLightSource) {
  SceneDesc d = halfBlackEmitterScene();
  d.meshes.erase(d.meshes.begin());
  EXPECT_THROW(Scene scene(std::move(d)), SceneError);
}

}  // namespace
}  // namespace pathlab
