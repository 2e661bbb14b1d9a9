// Tests of the glTF loader's materials and textures: factors and supported extensions, the
// default material, unsupported parts that warn, sRGB against linear decoding, 16-bit and
// external images.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

TEST(GltfMaterial, FactorsAndSupportedExtensions) {
  TestGltf g;
  g.add("materials", R"({"name":"all","doubleSided":true,
    "pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1,1],"metallicFactor":0.3,"roughnessFactor":0.7},
    "emissiveFactor":[1,0.5,0],
    "extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":4},
                  "KHR_materials_ior":{"ior":1.33},
                  "KHR_materials_specular":{"specularFactor":0.5,"specularColorFactor":[1,0.5,0.25]},
                  "KHR_materials_transmission":{"transmissionFactor":0.9}}})");
  g.members.push_back(R"("extensionsUsed":["KHR_materials_emissive_strength","KHR_materials_ior",
    "KHR_materials_specular","KHR_materials_transmission","KHR_lights_punctual"])");
  addTexturedTriangle(g);
  const SceneDesc d = loadGltf(g.write("material.gltf"));
  EXPECT_TRUE(d.warnings.empty()) << ::testing::PrintToString(d.warnings);
  ASSERT_EQ(d.materials.size(), 1u);
  const Material& m = d.materials[0];
  EXPECT_EQ(m.name, "all");
  EXPECT_TRUE(m.doubleSided);
  EXPECT_TRUE(m.isEmissive());
  EXPECT_FLOAT_EQ(m.emissiveStrength, 4.f);
  const MaterialPoint p = evalMaterial(m, Vec2(0.3f), d.textures);
  expectNear(p.baseColor, {0.5f, 0.25f, 1.f});
  EXPECT_FLOAT_EQ(p.metallic, 0.3f);
  EXPECT_FLOAT_EQ(p.roughness, 0.7f);
  EXPECT_FLOAT_EQ(p.ior, 1.33f);
  EXPECT_FLOAT_EQ(p.specularFactor, 0.5f);
  expectNear(p.specularColor, {1.f, 0.5f, 0.25f});
  EXPECT_FLOAT_EQ(p.transmission, 0.9f);
  expectNear(evalEmission(m, Vec2(0.3f), d.textures), {4.f, 2.f, 0.f});
}

TEST(GltfMaterial, APrimitiveWithoutMaterialGetsTheAppendedDefault) {
  TestGltf g;
  g.add("materials", R"({"name":"unused","pbrMetallicRoughness":{"metallicFactor":0}})");
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(g.vec3(kTriangle))})) + "}");
  const SceneDesc d = loadGltf(g.write("default-material.gltf"));
  ASSERT_EQ(d.materials.size(), 2u);
  ASSERT_EQ(d.meshes.size(), 1u);
  EXPECT_EQ(d.meshes[0].material, 1);
  const MaterialPoint p = evalMaterial(d.materials[1], Vec2(0.f), d.textures);
  expectNear(p.baseColor, Vec3(1.f));
  EXPECT_FLOAT_EQ(p.metallic, 1.f);
  EXPECT_FLOAT_EQ(p.roughness, 1.f);
}

TEST(GltfMaterial, UnsupportedPartsOfExtensionsWarn) {
  TestGltf g;
  const std::string png = encodePng(1, 1, 3, 8, {255, 255, 255});
  g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  g.add("textures", R"({"source":0})");
  g.add("materials", R"({"extensions":{"KHR_materials_specular":{"specularTexture":{"index":0}},
                  "KHR_materials_transmission":{"transmissionFactor":1,"transmissionTexture":{"index":0}}}})");
  addTexturedTriangle(g);
  const SceneDesc d = loadGltf(g.write("unsupported-parts.gltf"));
  for (const char* needle : {"KHR_materials_specular textures", "KHR_materials_transmission texture"}) {
    EXPECT_TRUE(hasWarning(d, needle)) << needle << ::testing::PrintToString(d.warnings);
  }
  EXPECT_FLOAT_EQ(d.materials[0].transmissionFactor, 1.f);
}

TEST(GltfTexture, ColourTexturesAreSrgbDecodedAndDataTexturesLinear) {
  // One 2 x 1 image used as base colour (sRGB), metallic-roughness (linear) and emissive (sRGB).
  TestGltf g;
  const std::string png = encodePng(2, 1, 4, 8, {128, 64, 255, 255, 0, 255, 0, 128});
  g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  g.add("samplers", R"({"magFilter":9728,"wrapS":33071,"wrapT":33648})");
  g.add("textures", R"({"source":0,"sampler":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0},
    "metallicRoughnessTexture":{"index":0}},"emissiveFactor":[1,1,1],
    "emissiveTexture":{"index":0,"texCoord":1}})");
  addTexturedTriangle(g);
  const SceneDesc d = loadGltf(g.write("srgb.gltf"));
  ASSERT_EQ(d.textures.size(), 2u);  // sRGB and linear views of the same image
  const Material& m = d.materials[0];
  const Texture& srgb = d.textures[size_t(m.baseColorTexture.texture)];
  const Texture& linear = d.textures[size_t(m.metallicRoughnessTexture.texture)];
  EXPECT_EQ(m.emissiveTexture.texture, m.baseColorTexture.texture);
  ASSERT_EQ(srgb.width, 2);
  ASSERT_EQ(srgb.height, 1);
  // Held once, as the file's 8-bit RGBA, shared by both views.
  ASSERT_TRUE(srgb.bytes && linear.bytes);
  EXPECT_EQ(srgb.bytes, linear.bytes);
  EXPECT_EQ(srgb.channels, 4);
  EXPECT_EQ(srgb.texelBytes(), 8u);
  EXPECT_TRUE(srgb.srgb);
  EXPECT_FALSE(linear.srgb);
  EXPECT_FLOAT_EQ(srgb.fetch(0, 0).r, srgbToLinear(128.f / 255.f));
  EXPECT_FLOAT_EQ(srgb.fetch(0, 0).g, srgbToLinear(64.f / 255.f));
  EXPECT_FLOAT_EQ(srgb.fetch(0, 0).b, 1.f);
  EXPECT_FLOAT_EQ(srgb.fetch(1, 0).a, 128.f / 255.f);  // alpha is linear
  EXPECT_FLOAT_EQ(linear.fetch(0, 0).r, 128.f / 255.f);
  EXPECT_FLOAT_EQ(linear.fetch(0, 0).g, 64.f / 255.f);
  EXPECT_EQ(srgb.wrapS, WrapMode::ClampToEdge);
  EXPECT_EQ(srgb.wrapT, WrapMode::MirroredRepeat);
  EXPECT_TRUE(srgb.nearest);
  // metallic = factor x B, roughness = factor x G of the linear texel.
  const MaterialPoint p = evalMaterial(m, Vec2(0.25f, 0.5f), d.textures);
  EXPECT_FLOAT_EQ(p.metallic, 1.f);
  EXPECT_FLOAT_EQ(p.roughness, 64.f / 255.f);
  EXPECT_FLOAT_EQ(p.baseColor.r, srgbToLinear(128.f / 255.f));
  EXPECT_TRUE(hasWarning(d, "TEXCOORD_1")) << ::testing::PrintToString(d.warnings);
}

TEST(GltfTexture, SixteenBitImagesKeepTheirPrecision) {
  TestGltf g;
  const std::string png = encodePng(1, 1, 3, 16, {1000, 32768, 65535});
  g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  g.add("textures", R"({"source":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"metallicRoughnessTexture":{"index":0}}})");
  addTexturedTriangle(g);
  const SceneDesc d = loadGltf(g.write("sixteen.gltf"));
  ASSERT_EQ(d.textures.size(), 1u);
  EXPECT_FALSE(d.textures[0].bytes);  // 16-bit images keep the float path
  EXPECT_FLOAT_EQ(d.textures[0].fetch(0, 0).r, 1000.f / 65535.f);
  EXPECT_FLOAT_EQ(d.textures[0].fetch(0, 0).g, 32768.f / 65535.f);
  EXPECT_EQ(d.textures[0].wrapS, WrapMode::Repeat);  // no sampler: REPEAT, linear filtering
  EXPECT_FALSE(d.textures[0].nearest);
}

TEST(GltfTexture, ExternalImageFilesAreFoundNextToTheGltf) {
  TestGltf g;
  writeFile("external-texture.png", encodePng(1, 1, 3, 8, {0, 255, 0}));
  g.add("images", R"({"uri":"external-texture.png"})");
  g.add("textures", R"({"source":0})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}})");
  addTexturedTriangle(g);
  const SceneDesc d = loadGltf(g.write("external-image.gltf"));
  ASSERT_EQ(d.textures.size(), 1u);
  EXPECT_EQ(d.textures[0].channels, 3);  // the file's RGB, not expanded to RGBA
  EXPECT_EQ(d.textures[0].fetch(0, 0), Vec4(0, 1, 0, 1));
}

}  // namespace
}  // namespace pathlab
