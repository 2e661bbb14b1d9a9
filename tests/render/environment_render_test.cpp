// Closed forms under an environment light, for every estimator (the path tracer, light tracing and
// the bidirectional path tracer under each heuristic): a convex Lambertian object of albedo rho in
// a uniform environment L reflects rho L everywhere (the white furnace of an environment: no path
// meets the object twice, and it sends back rho of the irradiance pi L it receives); a floor under
// an environment that is L above the horizon and 0 below receives irradiance pi L and shows rho L.
// Then the estimators agree on an environment-lit scene with a glossy and a glass object. Region
// means by z-tests with standard errors measured from independent passes; fixed seeds.
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using test::kFamilyAlpha;

std::shared_ptr<const EnvironmentDesc> constantEnvironment(float L) {
  auto d = std::make_shared<EnvironmentDesc>();
  d->constant = Spectrum(L);
  d->source = "test";
  return d;
}

// L in the map's upper half (theta < pi / 2, y > 0), 0 below: 8 x 2 texels, one row each.
std::shared_ptr<const EnvironmentDesc> upperHemisphere(float L) {
  auto d = std::make_shared<EnvironmentDesc>();
  d->width = 8;
  d->height = 2;
  d->texels.assign(16, Spectrum(0.f));
  for (int x = 0; x < 8; ++x) d->texels[static_cast<size_t>(x)] = Spectrum(L);
  d->source = "test";
  return d;
}

// An axis-aligned cube [-h, h]^3 with faces outward: convex, flat normals.
std::vector<TriangleMesh> outwardCube(float h, int material) {
  using test::quad;
  return {quad(Vec3(-h, -h, h), Vec3(h, -h, h), Vec3(h, h, h), Vec3(-h, h, h), material),       // +z
          quad(Vec3(h, -h, -h), Vec3(-h, -h, -h), Vec3(-h, h, -h), Vec3(h, h, -h), material),   // -z
          quad(Vec3(h, -h, h), Vec3(h, -h, -h), Vec3(h, h, -h), Vec3(h, h, h), material),       // +x
          quad(Vec3(-h, -h, -h), Vec3(-h, -h, h), Vec3(-h, h, h), Vec3(-h, h, -h), material),   // -x
          quad(Vec3(-h, h, h), Vec3(h, h, h), Vec3(h, h, -h), Vec3(-h, h, -h), material),       // +y
          quad(Vec3(-h, -h, -h), Vec3(h, -h, -h), Vec3(h, -h, h), Vec3(-h, -h, h), material)};  // -y
}

// Lambertian meshes of albedo rho under `environment`, seen by `camera`: nothing else emits.
Scene environmentLit(float rho, std::vector<TriangleMesh> meshes, const CameraDesc& camera,
                     std::shared_ptr<const EnvironmentDesc> environment) {
  SceneDesc desc;
  desc.path = "closed form";
  desc.materials.push_back(test::lambertian(rho));
  desc.meshes = std::move(meshes);
  desc.camera = camera;
  desc.environment = std::move(environment);
  return Scene(std::move(desc));
}

struct Estimator {
  const char* name;
  IntegratorKind kind;
  MisHeuristic heuristic;
  int passes;
};
const Estimator kEstimators[] = {{"pt", IntegratorKind::Pt, MisHeuristic::Power, 32},
                                 {"balance", IntegratorKind::Bpt, MisHeuristic::Balance, 32},
                                 {"power", IntegratorKind::Bpt, MisHeuristic::Power, 32},
                                 {"uniform", IntegratorKind::Bpt, MisHeuristic::Uniform, 32},
                                 {"lt", IntegratorKind::Lt, MisHeuristic::Balance, 256}};

// Every estimator's mean over each label set against its expected value (per label set; light
// tracing only on the sets flagged `ltToo`: it never sees the environment directly), one
// Bonferroni threshold for all comparisons.
void expectClosedForm(const Scene& scene, RenderSettings base, const std::vector<test::PixelLabels>& sets,
                      const std::vector<double>& expected, const std::vector<bool>& ltToo, const std::string& what) {
  int comparisons = 0;
  for (const Estimator& e : kEstimators)
    for (size_t i = 0; i < sets.size(); ++i) comparisons += (e.kind != IntegratorKind::Lt || ltToo[i]) ? 3 : 0;
  const double threshold = test::bonferroniZ(kFamilyAlpha, comparisons);
  uint64_t seed = 100 * test::testSeedBase() + 7;
  for (const Estimator& e : kEstimators) {
    RenderSettings s = base;
    s.integrator = e.kind;
    s.mis.heuristic = e.heuristic;
    s.seed = seed++;
    const std::vector<test::RegionMeans> means = test::renderRegionMeans(scene, s, e.passes, sets);
    for (size_t i = 0; i < sets.size(); ++i) {
      if (e.kind == IntegratorKind::Lt && !ltToo[i]) continue;
      EXPECT_EQ(means[i].discarded, 0u) << what << " " << e.name;
      for (int c = 0; c < 3; ++c) {
        const test::MeanEstimate& m = means[i].whole[static_cast<size_t>(c)];
        if (m.standardError == 0.0) {
          EXPECT_NEAR(m.mean, expected[i], 1e-5 * expected[i] + 1e-7) << what << " " << e.name << " set " << i;
          continue;
        }
        EXPECT_LT(std::abs(m.zScore(expected[i])), threshold)
            << what << " " << e.name << " set " << i << " channel " << c << ": " << m.mean << " vs " << expected[i]
            << " (se " << m.standardError << ")";
        EXPECT_LT(m.standardError, 0.03 * expected[i]) << what << " " << e.name << ": too few passes to see a bias";
      }
    }
  }
}

// A cube of albedo 0.6 in a uniform environment 0.8, seen corner-on: rho L = 0.48 on every pixel of
// the cube whatever its orientation, L = 0.8 on the background (no technique but s = 0 sees it).
TEST(EnvironmentClosedForm, ConvexObjectInUniformEnvironmentShowsRhoL) {
  const float rho = 0.6f, L = 0.8f;
  const Scene scene = environmentLit(rho, outwardCube(0.5f, 0),
                                     test::lookAt(Vec3(1.1f, 0.9f, 1.4f), Vec3(0.f), Vec3(0, 1, 0), 0.9f),
                                     constantEnvironment(L));
  RenderSettings base;
  base.width = base.height = 16;
  base.maxLength = 4;
  const test::PixelLabels all = test::gridLabels(16, 16, 1, 1);
  const auto anything = [](const Material&) { return true; };
  const test::PixelLabels cube = test::onlySeenDirectly(scene, base, all, anything);
  const test::PixelLabels sky = test::withoutSeenDirectly(scene, base, all, anything);
  ASSERT_GT(test::labelledPixels(cube), 40);
  ASSERT_GT(test::labelledPixels(sky), 40);
  expectClosedForm(scene, base, {cube, sky}, {rho * L, L}, {true, false}, "convex cube");
}

// A Lambertian floor (albedo 0.5) seen from above under L = 1.5 above the horizon, 0 below: the
// irradiance is pi L, the radiance rho L = 0.75 on every pixel (the camera sees only floor).
// Exercises the map's importance sampling (half the map is black) and its emission disk.
TEST(EnvironmentClosedForm, FloorUnderUpperHemisphereShowsRhoL) {
  const float rho = 0.5f, L = 1.5f;
  const Scene scene =
      environmentLit(rho, {test::quad(Vec3(-1, 0, 1), Vec3(1, 0, 1), Vec3(1, 0, -1), Vec3(-1, 0, -1), 0)},
                     test::lookAt(Vec3(0.f, 1.f, 0.01f), Vec3(0.f), Vec3(0, 1, 0), 1.f), upperHemisphere(L));
  RenderSettings base;
  base.width = base.height = 12;
  base.maxLength = 3;
  const test::PixelLabels all = test::gridLabels(12, 12, 1, 1);
  ASSERT_EQ(test::labelledPixels(test::onlySeenDirectly(scene, base, all, [](const Material&) { return true; })), 144);
  expectClosedForm(scene, base, {all}, {rho * L}, {true}, "floor");
}

// A sky for the agreement test: a 32 x 16 map, a gradient above the horizon, dim ground below and a
// soft "sun" of 4 x 2 texels 30 times the sky. Not the bundled sky.hdr: its sun (radiance 1500 on
// 0.6 % of the sphere) gives the uniform heuristic's s = 0 hits of it after a diffuse bounce, each
// weighted 1/k, a variance far too heavy-tailed for a short render's measured standard error
// (Veach 1997, sec. 9.2: the reason the weights use the densities).
std::shared_ptr<const EnvironmentDesc> softSky() {
  auto d = std::make_shared<EnvironmentDesc>();
  d->width = 32;
  d->height = 16;
  d->rotationDegrees = 40.f;
  d->source = "soft sky";
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) {
      const bool sun = x >= 20 && x < 24 && y >= 4 && y < 6;
      d->texels.push_back(sun ? Spectrum(30.f, 27.f, 22.f)
                          : y < 8 ? Spectrum(0.4f + 0.05f * y, 0.6f + 0.03f * y, 1.f)
                                  : Spectrum(0.12f, 0.1f, 0.08f));
    }
  return d;
}

// tests/scenes/environment.gltf (a rough gold sphere, a glass sphere, a box, a floor, nothing
// touching) under softSky: the path tracer, light tracing and the bidirectional tracer under the
// balance, power and uniform heuristics estimate the same image, region by region. Light tracing
// is compared away from the glass sphere (a pinhole cannot connect to a delta surface).
TEST(EnvironmentAgreement, GlossyAndGlassUnderASky) {
  const std::string source = PATHLAB_SOURCE_DIR;
  LoadOptions load;
  load.environment = softSky();
  const Scene scene(loadGltf(source + "/tests/scenes/environment.gltf", load));
  RenderSettings base;
  base.width = base.height = 16;
  base.maxLength = 5;
  const test::PixelLabels grid = test::gridLabels(16, 16, 4, 4);
  const test::PixelLabels clear = test::withoutSeenDirectly(scene, base, grid, test::hasDeltaLobe, 8);
  const uint64_t seed = 1000 * test::testSeedBase() + 31;
  const std::vector<test::EstimatorSpec> estimators = {
      test::estimatorSpec("pt", base, IntegratorKind::Pt, MisHeuristic::Power, seed, 1024),
      test::estimatorSpec("balance", base, IntegratorKind::Bpt, MisHeuristic::Balance, seed + 1, 256),
      test::estimatorSpec("power", base, IntegratorKind::Bpt, MisHeuristic::Power, seed + 2, 256),
      test::estimatorSpec("uniform", base, IntegratorKind::Bpt, MisHeuristic::Uniform, seed + 3, 512),
      test::estimatorSpec("lt", base, IntegratorKind::Lt, MisHeuristic::Balance, seed + 4, 2048)};
  const test::AgreementRun run = test::runAgreement(
      scene, estimators, {grid, clear},
      {{"balance", "pt"}, {"power", "pt"}, {"uniform", "pt"}, {"lt", "pt", 1}, {"power", "balance"}, {"lt", "power", 1}},
      kFamilyAlpha);
  std::cout << run.summary();
  test::expectAgreement(run, "environment");
}

}  // namespace
}  // namespace pathlab
