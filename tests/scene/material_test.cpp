// Tests of Texture sampling (filtering, wrap modes, sRGB transfer) and of material evaluation
// (factors times texture channels, emission).
#include "core/scene/material.h"
#include "core/texture/texture.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

#include <limits>

namespace pathlab {
namespace {

using namespace gltf_test;

// ---- Texture ---------------------------------------------------------------------------------

Texture makeTexture(int w, int h, std::vector<Vec4> texels, WrapMode wrap = WrapMode::Repeat) {
  Texture t;
  t.width = w;
  t.height = h;
  t.texels = std::move(texels);
  t.wrapS = t.wrapT = wrap;
  return t;
}

TEST(TextureSample, BilinearInterpolatesBetweenTexelCentres) {
  const Texture t = makeTexture(2, 1, {Vec4(0.f), Vec4(1.f)}, WrapMode::ClampToEdge);
  EXPECT_FLOAT_EQ(t.sample({0.25f, 0.5f}).r, 0.f);  // centre of texel 0
  EXPECT_FLOAT_EQ(t.sample({0.5f, 0.5f}).r, 0.5f);
  EXPECT_FLOAT_EQ(t.sample({0.625f, 0.5f}).r, 0.75f);
  EXPECT_FLOAT_EQ(t.sample({0.75f, 0.5f}).r, 1.f);
  EXPECT_FLOAT_EQ(t.sample({0.f, 0.5f}).r, 0.f);  // clamped edge
  EXPECT_FLOAT_EQ(t.sample({-3.f, 0.5f}).r, 0.f);
  EXPECT_FLOAT_EQ(t.sample({7.f, 0.5f}).r, 1.f);
}

TEST(TextureSample, WrapModesAtAndBeyondTheEdges) {
  const Texture repeat = makeTexture(2, 1, {Vec4(0.f), Vec4(1.f)}, WrapMode::Repeat);
  EXPECT_FLOAT_EQ(repeat.sample({0.f, 0.5f}).r, 0.5f);  // halfway between texel 1 and texel 0
  EXPECT_FLOAT_EQ(repeat.sample({1.25f, 0.5f}).r, 0.f);
  EXPECT_FLOAT_EQ(repeat.sample({-0.25f, 0.5f}).r, 1.f);
  const Texture mirror = makeTexture(2, 1, {Vec4(0.f), Vec4(1.f)}, WrapMode::MirroredRepeat);
  EXPECT_FLOAT_EQ(mirror.sample({1.25f, 0.5f}).r, 1.f);  // mirror image of u = 0.75
  EXPECT_FLOAT_EQ(mirror.sample({1.75f, 0.5f}).r, 0.f);
  EXPECT_FLOAT_EQ(mirror.sample({-0.25f, 0.5f}).r, 0.f);  // mirror image of u = 0.25
  EXPECT_FLOAT_EQ(mirror.sample({1.f, 0.5f}).r, 1.f);     // the edge texel, repeated
}

TEST(TextureSample, NearestPicksTheTexelUnderTheCoordinate) {
  Texture t = makeTexture(2, 2, {Vec4(0.f), Vec4(1.f), Vec4(2.f), Vec4(3.f)});
  t.nearest = true;
  EXPECT_FLOAT_EQ(t.sample({0.49f, 0.01f}).r, 0.f);
  EXPECT_FLOAT_EQ(t.sample({0.51f, 0.01f}).r, 1.f);
  EXPECT_FLOAT_EQ(t.sample({0.2f, 0.7f}).r, 2.f);   // row 1 is the lower half (v grows down)
  EXPECT_FLOAT_EQ(t.sample({1.7f, -0.3f}).r, 3.f);  // repeat
}

TEST(TextureSample, HugeAndNonFiniteCoordinatesStayInBounds) {
  const Texture t = makeTexture(3, 3, std::vector<Vec4>(9, Vec4(0.5f)));
  for (WrapMode mode : {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat}) {
    Texture w = t;
    w.wrapS = w.wrapT = mode;
    for (float u : {1e30f, -1e30f, std::numeric_limits<float>::quiet_NaN(),
                    std::numeric_limits<float>::infinity(), 3e9f}) {
      EXPECT_FLOAT_EQ(w.sample({u, u}).r, 0.5f);
    }
  }
  EXPECT_EQ(Texture{}.sample({0.5f, 0.5f}), Vec4(0.f));  // an empty texture is black
}

TEST(TextureSample, AverageIsTheMeanTexel) {
  const Texture t = makeTexture(2, 2, {Vec4(0.f), Vec4(1.f), Vec4(2.f), Vec4(5.f)});
  EXPECT_EQ(t.average(), Vec4(2.f));
  EXPECT_EQ(Texture{}.average(), Vec4(0.f));
}

TEST(TextureSrgb, TransferFunctionsMatchIec61966AndInvertEachOther) {
  EXPECT_FLOAT_EQ(srgbToLinear(0.f), 0.f);
  EXPECT_FLOAT_EQ(srgbToLinear(1.f), 1.f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.2140411f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.04045f), 0.04045f / 12.92f, 1e-7f);
  EXPECT_NEAR(linearToSrgb(0.2140411f), 0.5f, 1e-6f);
  for (int i = 0; i <= 255; ++i) {
    const float v = float(i) / 255.f;
    EXPECT_NEAR(linearToSrgb(srgbToLinear(v)), v, 2e-6f) << i;
  }
}

// ---- Material --------------------------------------------------------------------------------

TEST(MaterialEval, FactorsTimesTextureChannels) {
  std::vector<Texture> textures = {
      makeTexture(1, 1, {Vec4(0.5f, 0.25f, 1.f, 1.f)}),  // base colour (already linear)
      makeTexture(1, 1, {Vec4(0.9f, 0.6f, 0.4f, 1.f)}),  // metallic-roughness: G, B
      makeTexture(1, 1, {Vec4(0.5f, 1.f, 0.f, 1.f)}),    // emissive
  };
  Material m;
  m.baseColorFactor = Vec4(0.5f, 1.f, 0.5f, 1.f);
  m.baseColorTexture = TextureRef{0};
  m.metallicFactor = 0.5f;
  m.roughnessFactor = 0.5f;
  m.metallicRoughnessTexture = TextureRef{1};
  m.emissiveFactor = Spectrum(2.f, 1.f, 1.f);
  m.emissiveStrength = 3.f;
  m.emissiveTexture = TextureRef{2};
  m.ior = 1.7f;
  m.specularFactor = 0.25f;
  m.specularColorFactor = Spectrum(1.f, 0.f, 0.5f);
  m.transmissionFactor = 0.5f;
  const MaterialPoint p = evalMaterial(m, Vec2(0.3f, 0.6f), textures);
  expectNear(p.baseColor, {0.25f, 0.25f, 0.5f});
  EXPECT_FLOAT_EQ(p.metallic, 0.5f * 0.4f);
  EXPECT_FLOAT_EQ(p.roughness, 0.5f * 0.6f);
  EXPECT_FLOAT_EQ(p.ior, 1.7f);
  EXPECT_FLOAT_EQ(p.specularFactor, 0.25f);
  expectNear(p.specularColor, {1.f, 0.f, 0.5f});
  EXPECT_FLOAT_EQ(p.transmission, 0.5f);
  expectNear(evalEmission(m, Vec2(0.3f, 0.6f), textures), {3.f, 3.f, 0.f});
}

TEST(MaterialEval, NoEmissionWithoutFactorAndStaleTexturesReadWhite) {
  Material m;
  EXPECT_EQ(evalEmission(m, Vec2(0.f), {}), Spectrum(0.f));
  m.emissiveFactor = Spectrum(1.f);
  m.emissiveStrength = 0.f;
  EXPECT_EQ(evalEmission(m, Vec2(0.f), {}), Spectrum(0.f));
  m.emissiveStrength = 2.f;
  m.emissiveTexture = TextureRef{5};  // no such texture: neutral, never out of bounds
  m.baseColorTexture = TextureRef{5};
  EXPECT_EQ(evalEmission(m, Vec2(0.f), {}), Spectrum(2.f));
  EXPECT_EQ(evalMaterial(m, Vec2(0.f), {}).baseColor, Spectrum(1.f));
}

}  // namespace
}  // namespace pathlab
