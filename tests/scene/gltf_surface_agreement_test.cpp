// Agreement of the path tracer, light tracing and BPT on scenes with the surfaces real glTF
// models have: a normal-mapped floor (the shading normals varying per texel go through the
// BSDF's shading-normal handling and Veach's adjoint correction on light subpaths, Veach 1997,
// sec. 5.3) and alpha-masked / blended occluders (cut-outs and stochastic transparency seen by
// traced rays, shadow rays and t = 1 connections alike). Region z-tests with standard errors
// measured from independent passes (tests/support/agreement.h); fixed seeds.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_surface_scenes.h"
#include "tests/support/agreement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

using namespace gltf_test;

using test::kFamilyAlpha;

test::AgreementRun run(const Scene& scene, int pt, int bpt, int lt) {
  RenderSettings base;
  base.width = 16;
  base.height = 16;
  base.maxLength = 4;
  const test::PixelLabels grid = test::gridLabels(base.width, base.height, 4, 4);
  std::vector<test::EstimatorSpec> estimators;
  uint64_t seed = 1000 * test::testSeedBase() + 77;
  auto add = [&](const std::string& name, IntegratorKind kind, int n) {
    RenderSettings s = base;
    s.integrator = kind;
    s.seed = seed++;
    estimators.push_back({name, s, n});
  };
  add("pt", IntegratorKind::Pt, pt);
  add("bpt", IntegratorKind::Bpt, bpt);
  add("lt", IntegratorKind::Lt, lt);
  return test::runAgreement(scene, estimators, {grid}, {{"bpt", "pt"}, {"lt", "pt"}, {"lt", "bpt"}},
                            kFamilyAlpha);
}

using test::report;

// A diffuse floor with a bumpy normal map (4 x 4 texels of tilts up to ~40 degrees, bilinear,
// tiled twice) beside a diffuse wall, lit by a point light; the camera looks down.
TEST(SurfaceAgreement, NormalMappedFloor) {
  TestGltf g;
  std::vector<uint16_t> texels;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) {
      const float a = 1.7f * float(x) + 2.3f * float(y);
      texels.push_back(uint16_t(128 + 80 * std::sin(a)));
      texels.push_back(uint16_t(128 + 80 * std::cos(1.3f * a)));
      texels.push_back(200);
    }
  }
  addImageTexture(g, 4, 4, 3, texels);
  g.add("materials", R"({"pbrMetallicRoughness":{"metallicFactor":0,"baseColorFactor":[0.8,0.8,0.8,1]},
    "normalTexture":{"index":0}})");
  g.add("materials", R"({"pbrMetallicRoughness":{"metallicFactor":0,"baseColorFactor":[0.7,0.5,0.3,1]}})");
  addQuad(g, Vec3(0.f), Vec3(0, 0, 1.5f), Vec3(1.5f, 0, 0), 0, 2.f);  // floor, normal +y
  addQuad(g, Vec3(-1.f, 0.75f, 0), Vec3(0, 0.75f, 0), Vec3(0, 0, 1.5f), 1);  // wall facing +x
  addCameraAndLight(g, 2.2f, Vec3(0.6f, 1.2f, 0.3f), 3.f);  // the light outside the view
  const Scene scene(loadGltf(g.write("agreement-normal-map.gltf")));
  ASSERT_FALSE(scene.meshes()[0].tangents.empty());
  const auto r = run(scene, 512, 192, 1536);
  report(r, "normal-mapped floor");
  test::expectAgreement(r, "normal-mapped floor");
}

// A diffuse floor under a MASK occluder (a 4 x 4 checker of holes) and a BLEND sheet (alpha
// 0.4), lit by a point light above them and the camera: the floor's shadows come through holes
// and sheet, and the camera sees the floor through them.
TEST(SurfaceAgreement, AlphaMaskedAndBlendedOccluders) {
  TestGltf g;
  g.add("samplers", R"({"magFilter":9728})");
  std::vector<uint16_t> checker;
  for (int y = 0; y < 4; ++y) {
    for (int x = 0; x < 4; ++x) checker.insert(checker.end(), {200, 200, 200, uint16_t((x + y) % 2 ? 255 : 0)});
  }
  addImageTexture(g, 4, 4, 4, checker, 0);
  g.add("materials", R"({"pbrMetallicRoughness":{"metallicFactor":0,"baseColorFactor":[0.8,0.8,0.8,1]}})");
  g.add("materials", R"({"alphaMode":"MASK","pbrMetallicRoughness":{"metallicFactor":0,
    "baseColorTexture":{"index":0}},"doubleSided":true})");
  g.add("materials", R"({"alphaMode":"BLEND","pbrMetallicRoughness":{"metallicFactor":0,
    "baseColorFactor":[0.3,0.6,0.9,0.4]},"doubleSided":true})");
  addQuad(g, Vec3(0.f), Vec3(0, 0, 1.5f), Vec3(1.5f, 0, 0), 0);                // floor
  addQuad(g, Vec3(-0.4f, 0.6f, 0), Vec3(0.5f, 0, 0), Vec3(0, 0, -0.5f), 1);    // mask, up
  addQuad(g, Vec3(0.5f, 0.4f, 0.2f), Vec3(0.4f, 0, 0), Vec3(0, 0, -0.4f), 2);  // blend, up
  // The light above the camera: a point light in view is a path (s = 1, t = 1) only light
  // tracing can splat, which no path tracer can compare.
  addCameraAndLight(g, 2.2f, Vec3(0.1f, 2.6f, 0.f), 8.f);
  const Scene scene(loadGltf(g.write("agreement-alpha.gltf")));
  const auto r = run(scene, 512, 192, 1536);
  report(r, "alpha occluders");
  test::expectAgreement(r, "alpha occluders");
}

}  // namespace
}  // namespace pathlab
