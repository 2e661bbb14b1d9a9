// Near-coincident connections (MisOptions::minConnection): a technique whose connection edge is
// shorter than the threshold is left out of the set misWeight weighs for that path, whenever an
// enabled technique that samples the edge instead remains. The estimate must stay unbiased
// (Veach 1997 eq. 9.2 holds for any technique set chosen as a function of the path alone) and the
// weighted connections must lose their unbounded 1/d^2. Fixed seeds; PATHLAB_TEST_SEED reruns
// them with others.
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"
#include "tests/support/image_means.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using test::EstimatorSpec;
using test::PairSpec;

using test::kFamilyAlpha;

RenderSettings settings(IntegratorKind kind, MisHeuristic h, float minConnection, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = 16;
  s.maxLength = 6;
  s.integrator = kind;
  s.mis.heuristic = h;
  s.mis.minConnection = minConnection;
  s.seed = 1000 * test::testSeedBase() + seed;
  return s;
}

// A threshold of 30 % of the bounding radius leaves out a large share of all connections in the
// Cornell box (every one within 0.3 of a wall's neighbour, of the light, of the camera): every
// heuristic over what remains, and light tracing (whose short camera connections have no other
// technique and stay), still estimate the path tracer's image, region by region. The uniform
// heuristic runs without s = 0: with it, every path would give its 1/k share to hitting the small
// light, a coin flip whose rare large samples make a short render's standard error unreliable
// (docs/benchmarks.md); without it, and with no connection shorter than 0.3, every weighted
// contribution is bounded.
TEST(ShortConnections, LeavingOutAThirdOfTheRoomKeepsEveryEstimatorUnbiased) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  RenderSettings uniform = settings(IntegratorKind::Bpt, MisHeuristic::Uniform, 0.3f, 4);
  uniform.techniques = TechniqueSet::parse("t=1;s=1;s=2;s=3;s=4;s=5;s=6");
  const std::vector<EstimatorSpec> estimators = {
      {"pt", settings(IntegratorKind::Pt, MisHeuristic::Balance, 0.f, 1), 768},
      {"balance", settings(IntegratorKind::Bpt, MisHeuristic::Balance, 0.3f, 2), 128},
      {"power", settings(IntegratorKind::Bpt, MisHeuristic::Power, 0.3f, 3), 128},
      {"uniform", uniform, 192},
      {"lt", settings(IntegratorKind::Lt, MisHeuristic::Balance, 0.3f, 5), 128},
  };
  const auto run = test::runAgreement(
      scene, estimators, {test::gridLabels(16, 16, 4, 4)},
      {{"balance", "pt"}, {"power", "pt"}, {"uniform", "pt"}, {"lt", "pt"}, {"uniform", "balance"}}, kFamilyAlpha);
  std::cout << run.summary();
  test::expectAgreement(run, "cornell-box, minConnection 0.3");
}

// The fallback: a point light (no s = 0) 0.05 above a floor, with only the path tracer's
// techniques s = 0 and s = 1 enabled. The next-event connections to the floor under the light are
// short, and no enabled technique samples that edge instead, so none may be left out: the image
// must equal the path tracer's. With every technique enabled, (2, t) samples the edge from the
// light and the short (1, t) are left out; that image must agree too.
TEST(ShortConnections, ThePathTracersTechniquesKeepEveryShortConnection) {
  SceneDesc desc = test::floorScene(0.5f);
  PunctualLightDesc light;
  light.position = Vec3(0.f, 0.05f, 0.f);
  light.intensity = 1e-2f;
  desc.punctualLights = {light};
  desc.camera = test::lookAt(Vec3(0.f, 0.5f, 0.5f), Vec3(0.f), Vec3(0, 1, 0), 0.5f);
  const Scene scene(std::move(desc));
  // Edges shorter than 0.2: those from the light to the floor within 0.19 of the spot under it
  // (most of the light it sheds there), none toward the camera.
  const float minConnection = 0.2f / scene.bounds().radius;

  RenderSettings s = settings(IntegratorKind::Pt, MisHeuristic::Balance, minConnection, 10);
  s.width = s.height = 12;
  s.maxLength = 3;
  // The light itself (k = 1, the (1,1) splat) is no path the tracer finds.
  s.techniques = TechniqueSet::parse("k=2;k=3");
  const test::MeanEstimate pt = test::seedMeans(scene, s, 8, 8, s.seed);
  ASSERT_GT(pt.mean, 0.0);
  s.integrator = IntegratorKind::Bpt;
  // The path tracer's techniques of lengths 2 and 3, then all of them.
  for (const char* techniques : {"0,3;1,2;0,4;1,3", "k=2;k=3"})
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Uniform}) {
      s.techniques = TechniqueSet::parse(techniques);
      s.mis.heuristic = h;
      const test::MeanEstimate bpt = test::seedMeans(scene, s, 8, 8, s.seed + 100);
      EXPECT_LT(std::abs(test::zDifference(bpt, pt)), 4.0)
          << techniques << " " << misHeuristicName(h) << ": " << bpt.mean << " +- " << bpt.standardError << " vs pt "
          << pt.mean << " +- " << pt.standardError;
    }
}

}  // namespace
}  // namespace pathlab
