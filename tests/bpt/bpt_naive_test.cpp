// Naive BPT (ConnectStrategy::Endpoints, the seed's "Naive BPT implementation"): each technique
// (s, t) on a light subpath of exactly s and a camera subpath of exactly t vertices of its own,
// joined at their endpoints. The techniques, their densities and so their MIS weights are those
// of path reuse (the weights are functions of the path alone), so the image has the same
// expectation: the furnace closed form, a partition of unity on every path, and region-by-region
// agreement with path reuse on the bundled scenes. Its cost is its own subpaths' rays, which the
// counters file under the technique.
#include "core/render/render_session.h"
#include "core/metrics/technique_table.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"
#include "tests/support/image_means.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using test::EstimatorSpec;
using test::MeanEstimate;
using test::PixelLabels;

using test::kMaxZ;
using test::kFamilyAlpha;

std::string naiveAssetPath(const std::string& name) { return std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name; }

RenderSettings naive(int width, int height, int maxLength, MisHeuristic h, uint64_t seed) {
  RenderSettings s;
  s.width = width;
  s.height = height;
  s.maxLength = maxLength;
  s.integrator = IntegratorKind::Bpt;
  s.mis.heuristic = h;
  s.connect = ConnectStrategy::Endpoints;
  s.seed = seed;
  return s;
}

// Le (1 - rho^K) / (1 - rho) at maximum length K, as bpt_render_test.cpp's BptFurnace, under
// the heuristic whose weights come from partial sums (balance, over each technique's own
// subpaths), from the explicit walk (a subset) and from the table (off); with Russian roulette.
TEST(NaiveBpt, FurnaceMatchesGeometricSeries) {
  const float rho = 0.6f, Le = 0.7f;
  const int K = 5;
  Scene scene(test::furnace(rho, Le));
  const double expected = Le * (1.0 - std::pow(rho, K)) / (1.0 - rho);
  struct Case {
    MisHeuristic h;
    const char* techniques;
    bool rr;
  };
  uint64_t seed = 71;
  for (const Case c : {Case{MisHeuristic::Balance, "all", false}, Case{MisHeuristic::Power, "s=0;s=1;t=1;2,2", false},
                       Case{MisHeuristic::Off, "all", false}, Case{MisHeuristic::Balance, "all", true}}) {
    RenderSettings s = naive(12, 12, K, c.h, seed++);
    s.techniques = TechniqueSet::parse(c.techniques);
    s.russianRoulette = c.rr;
    const MeanEstimate m = test::passMeans(scene, s, 64);
    EXPECT_LT(std::abs(m.zScore(expected)), kMaxZ)
        << misHeuristicName(c.h) << " " << c.techniques << " rr " << c.rr << ": mean " << m.mean << " expected "
        << expected << " se " << m.standardError;
    EXPECT_LT(m.standardError, 0.02 * expected);
  }
}

// Every weighted path's enabled weights sum to one (Counters::misPartitionFailures), with the
// partial sums of each technique's own subpaths.
TEST(NaiveBpt, WeightsArePartitionOfUnity) {
  Scene scene(loadGltf(naiveAssetPath("cornell-box.gltf")));
  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    RenderSettings s = naive(16, 16, 6, h, 5);
    s.checkMis = true;
    RenderSession session(scene, s);
    for (int i = 0; i < 4; ++i) session.renderPass();
    EXPECT_GT(session.counters().misPartitionChecks, 5000u);
    EXPECT_EQ(session.counters().misPartitionFailures, 0u) << misHeuristicName(h);
  }
}

// The cost: no shared walks; each technique's row holds its own subpaths' rays, which with the
// shadow rays are every ray of the render; per sample far more than path reuse.
TEST(NaiveBpt, RaysAreFiledUnderEachTechnique) {
  Scene scene(loadGltf(naiveAssetPath("cornell-box.gltf")));
  const int K = 5;
  RenderSession naiveSession(scene, naive(16, 16, K, MisHeuristic::Balance, 3));
  RenderSettings reuse = naive(16, 16, K, MisHeuristic::Balance, 3);
  reuse.connect = ConnectStrategy::All;
  RenderSession reuseSession(scene, reuse);
  for (int i = 0; i < 2; ++i) naiveSession.renderPass(), reuseSession.renderPass();
  const Counters& c = naiveSession.counters();
  EXPECT_EQ(c.cameraWalk.rays + c.lightWalk.rays, 0u);
  uint64_t walk = 0, shadow = 0;
  for (const Technique x : techniquesUpTo(K)) {
    const int s = x.s, t = x.t;
    const TechniqueCounters& tc = c.technique(s, t);
    walk += tc.walkRays;
    shadow += tc.shadowRays;
    EXPECT_GT(tc.tried, 0u) << s << "," << t;
    // (s, 1) traces no camera ray and (1, t >= 2) no light walk (next-event estimation): only
    // (1, 1) has no walk edge at all.
    if (!(s == 1 && t == 1)) EXPECT_GT(tc.walkRays, 0u) << s << "," << t;
    else EXPECT_EQ(tc.walkRays, 0u);
  }
  EXPECT_EQ(walk, c.rays);
  EXPECT_EQ(shadow, c.shadowRays);
  const std::vector<TechniqueRow> rows = techniqueRows(c, K, 1.0);
  ASSERT_FALSE(rows.empty());
  EXPECT_FALSE(rows.front().walk);  // no walk rows: the walks are the techniques'
  const TechniqueCounters& tc = c.technique(2, 3);
  for (const TechniqueRow& r : rows) {
    if (r.s == 2 && r.t == 3) {
      EXPECT_EQ(r.rays, tc.walkRays + tc.shadowRays);
    }
  }
  EXPECT_GT(c.totalRays(), 3 * reuseSession.counters().totalRays());
}

using test::report;

// Path reuse and naive BPT, both balance, region by region (bpt_agreement_test.cpp's method). On
// the bundled scenes with delta surfaces the pixels that see an emitter or a delta surface are
// left out as there (the same technique samples them under both, a coin flip worth the emitter).
void expectReuseAgreesWithNaive(const std::string& file, int width, int height, int maxLength, int passes,
                                const test::MaterialPredicate& leaveOut) {
  Scene scene(loadGltf(naiveAssetPath(file)));
  RenderSettings all = naive(width, height, maxLength, MisHeuristic::Balance, 1000 * test::testSeedBase() + 1);
  all.connect = ConnectStrategy::All;
  const RenderSettings endpoints = naive(width, height, maxLength, MisHeuristic::Balance, 1000 * test::testSeedBase() + 2);
  PixelLabels grid = test::gridLabels(width, height, 4, 4);
  if (leaveOut) grid = test::withoutSeenDirectly(scene, all, grid, leaveOut, 16);
  const auto run = test::runAgreement(scene, {{"all", all, passes}, {"endpoints", endpoints, passes}}, {grid},
                                      {{"endpoints", "all"}}, kFamilyAlpha);
  report(run, file);
  test::expectAgreement(run, file + " connect all vs endpoints");
}

using test::emitterOrDelta;

TEST(NaiveBptAgreement, CornellBox) { expectReuseAgreesWithNaive("cornell-box.gltf", 16, 16, 8, 128, {}); }
TEST(NaiveBptAgreement, VeachMis) { expectReuseAgreesWithNaive("veach-mis.gltf", 24, 16, 4, 256, emitterOrDelta); }
TEST(NaiveBptAgreement, Caustic) { expectReuseAgreesWithNaive("caustic.gltf", 16, 16, 6, 192, emitterOrDelta); }
TEST(NaiveBptAgreement, BidirLamp) { expectReuseAgreesWithNaive("bidir-lamp.gltf", 15, 15, 6, 96, {}); }

}  // namespace
}  // namespace pathlab
