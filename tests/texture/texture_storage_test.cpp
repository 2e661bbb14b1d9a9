// 8-bit texture storage: texels stay as the file's bytes and are decoded on lookup, giving what
// the loader's former float texels gave; an image is held once whatever uses it.
#include "core/math/rng.h"
#include "core/scene/material.h"
#include "core/texture/texture.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

// The float texels the loader stored before textures stayed 8-bit (its decode of 8-bit data,
// written out again): the oracle the 8-bit lookups must reproduce.
Texture floatOracle(const Texture& t8) {
  Texture f;
  f.width = t8.width;
  f.height = t8.height;
  f.wrapS = t8.wrapS;
  f.wrapT = t8.wrapT;
  f.nearest = t8.nearest;
  const int comp = t8.channels;
  for (int p = 0; p < t8.width * t8.height; ++p) {
    float c[4];
    for (int k = 0; k < comp; ++k) {
      const uint8_t v = (*t8.bytes)[size_t(p * comp + k)];
      const bool colour = t8.srgb && (comp >= 3 ? k < 3 : k == 0);
      c[k] = colour ? srgbToLinear(float(v) / 255.f) : float(v) / 255.f;
    }
    switch (comp) {
      case 1: f.texels.emplace_back(c[0], c[0], c[0], 1.f); break;
      case 2: f.texels.emplace_back(c[0], c[0], c[0], c[1]); break;
      case 3: f.texels.emplace_back(c[0], c[1], c[2], 1.f); break;
      default: f.texels.emplace_back(c[0], c[1], c[2], c[3]); break;
    }
  }
  return f;
}

Texture randomBytes(int w, int h, int channels, bool srgb, Pcg32& rng) {
  auto bytes = std::make_shared<std::vector<uint8_t>>(size_t(w * h * channels));
  for (uint8_t& b : *bytes) b = uint8_t(rng.nextU32() & 0xff);
  Texture t;
  t.width = w;
  t.height = h;
  t.channels = channels;
  t.srgb = srgb;
  t.bytes = bytes;
  return t;
}

TEST(TextureStorage, EightBitLookupsEqualTheFloatPath) {
  Pcg32 rng(31, 32);
  int compared = 0;
  for (int channels = 1; channels <= 4; ++channels) {
    for (bool srgb : {false, true}) {
      for (WrapMode wrap : {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat}) {
        for (bool nearest : {false, true}) {
          Texture t8 = randomBytes(5, 3, channels, srgb, rng);
          t8.wrapS = wrap;
          t8.wrapT = wrap == WrapMode::Repeat ? WrapMode::MirroredRepeat : WrapMode::Repeat;
          t8.nearest = nearest;
          const Texture f = floatOracle(t8);
          ASSERT_TRUE(t8.valid());
          EXPECT_EQ(t8.texelBytes(), size_t(5 * 3 * channels));  // not 16 bytes a texel
          for (int y = -4; y < 7; ++y) {
            for (int x = -6; x < 11; ++x) {
              const Vec4 a = t8.fetch(x, y), b = f.fetch(x, y);
              for (int c = 0; c < 4; ++c) ASSERT_NEAR(a[c], b[c], 1e-6f) << x << "," << y;
            }
          }
          for (int k = 0; k < 500; ++k) {
            const Vec2 uv = 6.f * rng.next2D() - Vec2(3.f);
            const Vec4 a = t8.sample(uv), b = f.sample(uv);
            for (int c = 0; c < 4; ++c) {
              ASSERT_NEAR(a[c], b[c], 1e-6f) << "channels " << channels << " srgb " << srgb
                                             << " uv " << uv.x << "," << uv.y;
            }
            ++compared;
          }
          EXPECT_NEAR(t8.average().r, f.average().r, 1e-6f);
        }
      }
    }
  }
  EXPECT_EQ(compared, 4 * 2 * 3 * 2 * 500);
}

TEST(TextureStorage, ShortOrMissingBytesReadAsBlack) {
  Texture t;
  t.width = 2;
  t.height = 2;
  t.channels = 3;
  t.bytes = std::make_shared<std::vector<uint8_t>>(11, uint8_t(255));  // 12 needed
  EXPECT_FALSE(t.valid());
  EXPECT_EQ(t.sample(Vec2(0.5f)), Vec4(0.f));
  EXPECT_EQ(t.average(), Vec4(0.f));
}

// One image used by three materials, as sRGB colour and as linear data, through two samplers:
// its pixels are decoded once and held once, every texture sharing them.
TEST(TextureStorage, AnImageIsHeldOnceWhateverUsesIt) {
  TestGltf g;
  const std::string png = encodePng(2, 2, 3, 8, {10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110, 120});
  g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  g.add("samplers", R"({"magFilter":9728})");
  g.add("textures", R"({"source":0})");
  g.add("textures", R"({"source":0,"sampler":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},
    "metallicRoughnessTexture":{"index":0}}})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":1}},
    "emissiveFactor":[1,1,1],"emissiveTexture":{"index":0}})");
  addTexturedTriangle(g, 0);
  addTexturedTriangle(g, 1);
  addTexturedTriangle(g, 2);
  const SceneDesc d = loadGltf(g.write("shared-image.gltf"));
  // (sampler none, sRGB), (none, linear), (NEAREST, sRGB): three views, one set of pixels.
  ASSERT_EQ(d.textures.size(), 3u);
  for (const Texture& t : d.textures) {
    ASSERT_TRUE(t.bytes);
    EXPECT_EQ(t.bytes, d.textures[0].bytes);
    EXPECT_EQ(t.channels, 3);
  }
  EXPECT_EQ(d.materials[0].baseColorTexture.texture, d.materials[1].baseColorTexture.texture);
  EXPECT_EQ(d.materials[0].baseColorTexture.texture, d.materials[2].emissiveTexture.texture);
  EXPECT_NE(d.materials[0].baseColorTexture.texture, d.materials[2].baseColorTexture.texture);
  EXPECT_TRUE(d.textures[size_t(d.materials[2].baseColorTexture.texture)].nearest);
  const Texture& linear = d.textures[size_t(d.materials[1].metallicRoughnessTexture.texture)];
  EXPECT_FALSE(linear.srgb);
  EXPECT_FLOAT_EQ(linear.fetch(1, 1).b, 120.f / 255.f);
  EXPECT_FLOAT_EQ(d.textures[0].fetch(1, 1).b, srgbToLinear(120.f / 255.f));
}

}  // namespace
}  // namespace pathlab
