// Tests of what real glTF models use beyond plain textures: KHR_texture_transform on every
// texture, TEXCOORD_1, COLOR_0, and warnings folded into one line per problem.
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "core/texture/texture_integral.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

using namespace gltf_test;

// A 2 x 2 RGB image, NEAREST: red (top left), green (top right), blue (bottom left), white.
void addQuadrantImage(TestGltf& g) {
  const std::string png =
      encodePng(2, 2, 3, 8, {255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255});
  g.add("images", R"({"uri":"data:image/png;base64,)" + base64(png) + "\"}");
  g.add("samplers", R"({"magFilter":9728})");
  g.add("textures", R"({"source":0,"sampler":0})");
}

TEST(GltfTextureTransform, OffsetRotationScaleAndTexCoordOfTheExtension) {
  TestGltf g;
  addQuadrantImage(g);
  // Material 0: offset by half the image in u; material 1: rotated by 90 degrees and scaled.
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,
    "extensions":{"KHR_texture_transform":{"offset":[0.5,0]}}}}})");
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,
    "extensions":{"KHR_texture_transform":{"rotation":1.5707963,"scale":[0.5,2],"texCoord":1}}}}})");
  g.members.push_back(R"("extensionsUsed":["KHR_texture_transform","KHR_lights_punctual"])");
  g.members.push_back(R"("extensionsRequired":["KHR_texture_transform"])");
  addTexturedTriangle(g, 0);
  addTexturedTriangle(g, 1);
  const SceneDesc d = loadGltf(g.write("texture-transform.gltf"));
  // Required KHR_texture_transform is no refusal; the one warning is the absent TEXCOORD_1.
  ASSERT_EQ(d.warnings.size(), 1u) << ::testing::PrintToString(d.warnings);
  EXPECT_EQ(d.warnings[0], "mesh 1: no TEXCOORD_1, which its material reads; TEXCOORD_0 used");
  ASSERT_EQ(d.textures.size(), 2u);  // one image, two transforms: two textures sharing the pixels
  EXPECT_EQ(d.textures[0].bytes, d.textures[1].bytes);
  const Material& shifted = d.materials[0];
  // uv (0.25, 0.25) is red untransformed; shifted by +0.5 in u it reads green.
  expectNear(evalMaterial(shifted, Vec2(0.25f, 0.25f), d.textures).baseColor, {0.f, 1.f, 0.f});
  expectNear(evalMaterial(shifted, Vec2(0.75f, 0.75f), d.textures).baseColor, {0.f, 0.f, 1.f});
  // The extension's texCoord overrides the textureInfo's.
  const Material& rotated = d.materials[1];
  EXPECT_EQ(rotated.baseColorTexture.texCoord, 1);
  // T R S with R = [cos sin; -sin cos] at 90 degrees: (u, v) -> (2 v, -0.5 u).
  const UvTransform& t = d.textures[size_t(rotated.baseColorTexture.texture)].transform;
  const Vec2 mapped = t.apply(Vec2(0.3f, 0.2f));
  EXPECT_NEAR(mapped.x, 0.4f, 1e-6f);
  EXPECT_NEAR(mapped.y, -0.15f, 1e-6f);
  const Vec2 mappedU = t.apply(Vec2(1.f, 0.f));
  EXPECT_NEAR(mappedU.x, 0.f, 1e-6f);
  EXPECT_NEAR(mappedU.y, -0.5f, 1e-6f);
  // Read through TEXCOORD_1: uv1 (0.1, 0.1) -> (0.2, -0.05), wrapped to (0.2, 0.95): blue.
  const ShadingInputs at{Vec2(0.9f, 0.9f), Vec2(0.1f, 0.1f), Spectrum(1.f)};
  expectNear(evalMaterial(rotated, at, d.textures).baseColor, {0.f, 0.f, 1.f});
}

TEST(GltfTextureTransform, TheTriangleMeanFollowsTheTransform) {
  // meanOverTriangle of a transformed texture is the mean over the transformed triangle.
  Texture tex;
  tex.width = 4;
  tex.height = 3;
  for (int i = 0; i < 12; ++i) tex.texels.push_back(Vec4(float(i % 5) / 4.f, float(i % 3) / 2.f, 0.25f, 1.f));
  Texture plain = tex;
  tex.transform = UvTransform::fromGltf(Vec2(0.3f, -0.2f), 0.7f, Vec2(1.5f, 0.8f));
  const Vec2 a(0.1f, 0.2f), b(0.9f, 0.4f), c(0.3f, 0.8f);
  const Vec4 got = meanOverTriangle(tex, a, b, c);
  const Vec4 want = meanOverTriangle(plain, tex.transform.apply(a), tex.transform.apply(b),
                                     tex.transform.apply(c));
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(got[k], want[k], 1e-6f) << k;
  EXPECT_GT(std::abs(got.r - meanOverTriangle(plain, a, b, c).r), 1e-3f);  // the transform matters
}

// One triangle with TEXCOORD_0, TEXCOORD_1 and COLOR_0 (`colorType` VEC4 float or VEC3 unsigned
// byte normalized), material 0.
std::string triangleWithAttributes(TestGltf& g, bool byteColours) {
  const std::vector<Vec2> uv0 = {{0, 0}, {1, 0}, {0, 1}};
  const std::vector<Vec2> uv1 = {{0.5f, 0.5f}, {1, 0.5f}, {0.5f, 1}};
  std::string colour;
  if (byteColours) {
    const std::vector<uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 0, 0, 0};
    colour = str(g.accessor(g.view(rgb.data(), rgb.size()), 5121, 3, "VEC3", 0, true));
  } else {
    const std::vector<Vec4> rgba = {{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 0}};
    colour = str(g.accessor(g.view(rgba.data(), rgba.size() * sizeof(Vec4)), 5126, 3, "VEC4"));
  }
  const std::string prim = R"({"attributes":{"POSITION":)" + str(g.vec3(kTriangle)) +
                           R"(,"NORMAL":)" + str(g.vec3(kUp)) + R"(,"TEXCOORD_0":)" +
                           str(g.vec2(uv0)) + R"(,"TEXCOORD_1":)" + str(g.vec2(uv1)) +
                           R"(,"COLOR_0":)" + colour + R"(},"material":0})";
  g.root(R"({"mesh":)" + str(g.mesh({prim})) + "}");
  return g.write(byteColours ? "attributes-byte.gltf" : "attributes-float.gltf");
}

// The hit of a ray straight down onto the xy-plane triangle at (x, y).
SurfaceHit hitAt(const Scene& scene, float x, float y) {
  const std::optional<SurfaceHit> hit = scene.intersect(Ray{Vec3(x, y, 1.f), Vec3(0.f, 0.f, -1.f)});
  EXPECT_TRUE(hit.has_value());
  return hit.value_or(SurfaceHit{});
}

TEST(GltfVertexAttributes, SecondUvSetAndVertexColoursReachTheMaterial) {
  TestGltf g;
  addQuadrantImage(g);
  // The base colour reads TEXCOORD_1, times COLOR_0, times the factor.
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,0.5,1],
    "baseColorTexture":{"index":0,"texCoord":1}}})");
  const Scene scene(loadGltf(triangleWithAttributes(g, false)));
  EXPECT_TRUE(scene.warnings().empty()) << ::testing::PrintToString(scene.warnings());
  const TriangleMesh& mesh = scene.meshes().at(0);
  ASSERT_EQ(mesh.uvs1.size(), mesh.positions.size());
  ASSERT_EQ(mesh.colors.size(), mesh.positions.size());
  // At barycentrics (0.5, 0.25, 0.25): uv1 = (0.625, 0.625) (the white quadrant), colour
  // 0.5 red + 0.25 green + 0.25 blue, alpha 0.5 + 0.125.
  const SurfaceHit hit = hitAt(scene, 0.25f, 0.25f);
  EXPECT_NEAR(hit.uv1.x, 0.625f, 1e-5f);
  EXPECT_NEAR(hit.uv1.y, 0.625f, 1e-5f);
  expectNear(hit.color, {0.5f, 0.25f, 0.25f});
  const MaterialPoint p =
      evalMaterial(scene.material(hit.material), ShadingInputs{hit.uv, hit.uv1, hit.color},
                   scene.textures());
  expectNear(p.baseColor, {0.5f, 0.25f, 0.125f});
  // Scene::bsdf takes the same inputs (its untextured shortcut must not drop the colour).
  EXPECT_FLOAT_EQ(evalAlpha(scene.material(0), hit.uv, hit.uv1, 0.625f, scene.textures()), 0.625f);
}

TEST(GltfVertexAttributes, NormalizedByteColoursAndTheUntexturedShortcut) {
  TestGltf g;
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorFactor":[0.5,1,1,1],"metallicFactor":0}})");
  const Scene scene(loadGltf(triangleWithAttributes(g, true)));
  const TriangleMesh& mesh = scene.meshes().at(0);
  ASSERT_EQ(mesh.colors.size(), 3u);
  EXPECT_EQ(mesh.colors[0], Vec4(1.f, 0.f, 0.f, 1.f));  // VEC3: opaque
  const SurfaceHit hit = hitAt(scene, 0.25f, 0.25f);
  expectNear(hit.color, {0.5f, 0.25f, 0.25f});
  // A Lambertian material (metallic 0) reflects baseColor / pi at normal incidence (up to the
  // dielectric layer the BSDF adds): the ratio of two colour channels is the colour's.
  const Bsdf coloured = scene.bsdf(hit.material, ShadingInputs{hit.uv, hit.uv1, hit.color}, hit.ns, hit.ng);
  const Bsdf white = scene.bsdf(hit.material, ShadingInputs{hit.uv, hit.uv1, Spectrum(1.f)}, hit.ns, hit.ng);
  const Vec3 wo = glm::normalize(Vec3(0.1f, 0.2f, 1.f)), wi = glm::normalize(Vec3(-0.3f, 0.1f, 1.f));
  const Spectrum fc = coloured.eval(wo, wi, TransportMode::Radiance).f;
  const Spectrum fw = white.eval(wo, wi, TransportMode::Radiance).f;
  EXPECT_LT(fc.r, fw.r);
  EXPECT_LT(fc.g, fw.g);
  EXPECT_NE(fc, fw);
}

TEST(GltfVertexAttributes, ATextureOnAMissingSecondUvSetWarnsAndReadsTheFirst) {
  TestGltf g;
  addQuadrantImage(g);
  g.add("materials", R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0,"texCoord":1}}})");
  addTexturedTriangle(g);
  const Scene scene(loadGltf(g.write("missing-uv1.gltf")));
  ASSERT_EQ(scene.warnings().size(), 1u) << ::testing::PrintToString(scene.warnings());
  EXPECT_NE(scene.warnings()[0].find("no TEXCOORD_1"), std::string::npos);
  const SurfaceHit hit = hitAt(scene, 0.25f, 0.25f);
  EXPECT_EQ(hit.uv1, hit.uv);
}

TEST(GltfWarnings, TheSameProblemOfManyObjectsIsOneLineWithACount) {
  TestGltf g;
  // Five meshes, each with one zero-area triangle beside a good one; one mesh with two.
  const std::vector<Vec3> positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {3, 0, 0}};
  for (int m = 0; m < 6; ++m) {
    std::vector<uint16_t> idx = {0, 1, 2, 0, 3, 4};
    if (m == 5) idx.insert(idx.end(), {1, 3, 4});
    g.root(R"({"mesh":)" +
           str(g.mesh({TestGltf::primitive(g.vec3(positions), g.indices(idx))},
                      "m" + std::to_string(m))) +
           "}");
  }
  const SceneDesc d = loadGltf(g.write("folded-warnings.gltf"));
  ASSERT_EQ(d.warnings.size(), 2u) << ::testing::PrintToString(d.warnings);
  EXPECT_EQ(d.warnings[0],
            "1 zero-area triangle dropped (5 times: mesh 0 'm0', mesh 1 'm1', mesh 2 'm2' and 2 "
            "more)");
  EXPECT_EQ(d.warnings[1], "mesh 5 'm5': 2 zero-area triangles dropped");
}

}  // namespace
}  // namespace pathlab
