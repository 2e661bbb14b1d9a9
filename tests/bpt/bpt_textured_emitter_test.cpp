// Every estimator on a textured emitter: a quad light whose emissive texture is half black, half
// bright (radiance varies over each triangle; light choice by the integrated power), seen directly
// and lighting a floor and a wall. The path tracer, light tracing and BPT under the balance and
// power heuristics agree region by region (z-tests with measured standard errors, one Bonferroni
// threshold, tests/support/agreement.h). Light tracing reaches the camera from the emitter itself
// only by reading its radiance where the light subpath started, so a light vertex that forgot its
// uv (the texel at uv (0, 0) is black here) shows as a dark emitter.
#include "core/scene/scene.h"
#include "tests/support/agreement.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using test::kFamilyAlpha;

SceneDesc texturedEmitterScene() {
  SceneDesc d;
  d.path = "textured-emitter";
  d.materials.push_back(test::lambertian(0.6f));
  d.materials.push_back(test::lambertian(0.5f, Spectrum(6.f, 5.f, 4.f)));
  d.materials.back().emissiveTexture.texture = 0;
  // Black for u <= 1/4, bright for u >= 3/4 (clamped, bilinear): black at uv (0, 0).
  Texture t;
  t.width = 2;
  t.height = 1;
  t.texels = {Vec4(0.f, 0.f, 0.f, 1.f), Vec4(1.f, 0.8f, 0.6f, 1.f)};
  t.wrapS = t.wrapT = WrapMode::ClampToEdge;
  d.textures.push_back(t);
  d.meshes.push_back(test::quad(Vec3(-2.f, 0.f, 2.f), Vec3(2.f, 0.f, 2.f), Vec3(2.f, 0.f, -2.f), Vec3(-2.f, 0.f, -2.f), 0));  // floor, +y
  d.meshes.push_back(test::quad(Vec3(-2.f, 0.f, -1.f), Vec3(2.f, 0.f, -1.f), Vec3(2.f, 2.f, -1.f), Vec3(-2.f, 2.f, -1.f), 0));  // wall, +z
  // The emitter at y = 1, facing down; u runs along x.
  d.meshes.push_back(test::quad(Vec3(-0.7f, 1.f, -0.5f), Vec3(0.7f, 1.f, -0.5f), Vec3(0.7f, 1.f, 0.5f), Vec3(-0.7f, 1.f, 0.5f), 1));
  d.camera = test::lookAt(Vec3(0.f, 0.35f, 2.2f), Vec3(0.f, 0.7f, 0.f), Vec3(0.f, 1.f, 0.f), 1.1f);
  return d;
}

TEST(TexturedEmitterAgreement, PtLtAndBptAgree) {
  const Scene scene(texturedEmitterScene());
  ASSERT_EQ(scene.lights().size(), 2u);
  RenderSettings base;
  base.width = 16;
  base.height = 16;
  base.maxLength = 3;
  const test::PixelLabels grid = test::gridLabels(base.width, base.height, 4, 4);
  std::vector<test::EstimatorSpec> estimators;
  uint64_t seed = 1000 * test::testSeedBase() + 101;
  auto add = [&](const std::string& name, IntegratorKind kind, MisHeuristic h, int passes) {
    RenderSettings s = base;
    s.integrator = kind;
    s.mis.heuristic = h;
    s.seed = seed++;
    estimators.push_back({name, s, passes});
  };
  add("pt", IntegratorKind::Pt, MisHeuristic::Balance, 512);
  add("balance", IntegratorKind::Bpt, MisHeuristic::Balance, 128);
  add("power", IntegratorKind::Bpt, MisHeuristic::Power, 128);
  add("lt", IntegratorKind::Lt, MisHeuristic::Balance, 256);
  const test::AgreementRun run = test::runAgreement(
      scene, estimators, {grid},
      {{"balance", "pt"}, {"power", "pt"}, {"lt", "pt"}, {"power", "balance"}, {"lt", "balance"}}, kFamilyAlpha);
  std::cout << run.summary();
  test::expectAgreement(run, "textured emitter");
}

}  // namespace
}  // namespace pathlab
