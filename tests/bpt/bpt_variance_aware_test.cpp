// Variance-aware MIS (Grittmann et al. 2019; core/bpt/variance_aware_mis.h): the factor estimate
// against its closed form on synthetic passes, what the factors say on the Cornell box, and the
// estimator's unbiasedness on every bundled scene (region agreement with the balance heuristic,
// and with the path tracer where it samples every path). The weights' partition of unity with
// factors, connections and merges, is in bpt_mis_test.cpp (MergeMis.PartitionOfUnity*); the same
// image at any thread count in render_reproducible_test.cpp.
#include "core/bpt/variance_aware_mis.h"
#include "core/render/render_session.h"
#include "core/render/variance_aware_regions.h"
#include "tests/support/agreement.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

namespace pathlab {
namespace variance_aware_test {

// One region (an 8 x 8 image), one technique per family of contribution: c = E[X^2] / Var[X] for
// independent samples X, whatever their mean.
TEST(VarianceAwareFactors, AreTheSecondMomentOverTheVarianceOfIndependentSamples) {
  VarianceAwareRegions regions = varianceAwareRegions(8, 8, passTiles(8, 8), kVarianceAwareCell);
  VarianceAwareFactors factors(8, 8, std::move(regions.regionOfPixel), regions.count, 3);
  ASSERT_EQ(factors.regions(), 1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  std::vector<VarianceAwareFactors::Splat> splats;
  const Technique camera{1, 2}, light{2, 1}, never{0, 3}, constant{1, 3};
  const int passes = 3000;
  for (int p = 0; p < passes; ++p) {
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const Vec2 pixel(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        // A camera technique: X uniform on (0, 1): E[X^2] = 1/3, Var = 1/12, c = 4.
        factors.add(camera, pixel, uniform(rng), splats);
        // A pixel-stratified technique without noise: V = 0, the largest factor.
        factors.add(constant, pixel, 0.25f + 0.01f * static_cast<float>(x), splats);
        // Light tracing: each of the pass's 64 light subpaths lands here with probability 1/2,
        // with X uniform: Y = X B, E[Y^2] = 1/6, Var = 1/6 - 1/16, c = 1.6.
        if (uniform(rng) < 0.5f) factors.add(light, pixel, uniform(rng), splats);
      }
    factors.addSplats(splats);
    EXPECT_TRUE(splats.empty());
    // The pilot passes weigh with the balance heuristic: no factors yet.
    if (p + 1 < kVarianceAwarePilotPasses) EXPECT_EQ(factors.factorsOfLength(0, 2), nullptr);
    factors.finishPass(1.0);
  }
  ASSERT_NE(factors.factorsOfLength(0, 2), nullptr);
  // V from n passes has a relative standard error of sqrt(2 / (n - 1)) (2.6 %); M's is smaller.
  const double se = std::sqrt(2.0 / (passes - 1));
  EXPECT_NEAR(factors.factor(0, camera), 4.0, 4.0 * 4 * se);
  EXPECT_NEAR(factors.factor(0, light), 1.6, 1.6 * 4 * se);
  EXPECT_EQ(factors.factorsOfLength(0, 2)[camera.slot()], factors.factor(0, camera));
  EXPECT_EQ(factors.factor(0, never), 1.f);
  EXPECT_EQ(factors.factor(0, constant), kVarianceAwareMaxFactor);
}

TEST(VarianceAwareFactors, RegionsLieInOneWorkItemAndCoverTheFilm) {
  for (const auto& [w, h] : {std::pair{64, 48}, std::pair{13, 7}, std::pair{300, 17}}) {
    const std::vector<PassTile> tiles = passTiles(w, h);
    VarianceAwareRegions regions = varianceAwareRegions(w, h, tiles, varianceAwareCell(w, h, 4));
    EXPECT_EQ(regions.cell, kVarianceAwareCell);
    const VarianceAwareFactors factors(w, h, std::move(regions.regionOfPixel), regions.count, 4);
    std::vector<int> itemOfRegion(static_cast<size_t>(factors.regions()), -1);
    for (size_t i = 0; i < tiles.size(); ++i)
      for (int y = tiles[i].y0; y < tiles[i].y1; ++y)
        for (int x = tiles[i].x0; x < tiles[i].x1; ++x) {
          const int r = factors.regionOf(Vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f));
          ASSERT_GE(r, 0);
          ASSERT_LT(r, factors.regions());
          int& item = itemOfRegion[static_cast<size_t>(r)];
          EXPECT_TRUE(item == -1 || item == static_cast<int>(i)) << w << "x" << h << " region " << r;
          item = static_cast<int>(i);
        }
    EXPECT_TRUE(std::all_of(itemOfRegion.begin(), itemOfRegion.end(), [](int i) { return i >= 0; }));
    EXPECT_EQ(factors.regionOf(Vec2(-0.5f, 1.f)), -1);
    EXPECT_EQ(factors.regionOf(Vec2(static_cast<float>(w), 0.f)), -1);
  }
}

// A large image at a long length takes coarser cells, so the tables stay near their budget.
TEST(VarianceAwareFactors, CellsGrowWithTheImageToKeepTheTablesInBudget) {
  EXPECT_EQ(varianceAwareCell(640, 480, 10), kVarianceAwareCell);
  const int cell = varianceAwareCell(3840, 2160, 10);
  EXPECT_GT(cell, kVarianceAwareCell);
  EXPECT_LE(varianceAwareBytes(3840, 2160, 10), kVarianceAwareBytes + uint64_t{3840} * 2160 * sizeof(int32_t));
}

// On the Cornell box every pixel's camera techniques take one sample a pass (stratified by
// pixel), while light tracing's splats land where they may: the factors favour next-event
// estimation (1, 2) over light tracing (2, 1) for direct light, as the paper's BPT results show.
// And they change the image (the same seed under balance gives other bits).
TEST(VarianceAwareMis, FavoursThePixelStratifiedTechniquesOnTheCornellBox) {
  const Scene scene = test::bundledScene("cornell-box");
  RenderSettings s;
  s.width = 48;
  s.height = 48;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Bpt;
  s.mis.heuristic = MisHeuristic::VarianceAware;
  RenderSession session(scene, s);
  for (int p = 0; p < 64; ++p) ASSERT_TRUE(session.renderPass());
  const VarianceAwareFactors* factors = session.varianceAwareFactors();
  ASSERT_NE(factors, nullptr);
  // Every one of the first 32 passes taught the factors, then one in 8 (passes 32, 40, 48, 56).
  EXPECT_EQ(factors->passes(), 36u);
  std::vector<float> nee, lt;
  for (int r = 0; r < factors->regions(); ++r) {
    nee.push_back(factors->factor(r, Technique{1, 2}));
    lt.push_back(factors->factor(r, Technique{2, 1}));
  }
  auto median = [](std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  EXPECT_GT(median(nee), 3.f * median(lt)) << "median factor (1,2) " << median(nee) << ", (2,1) " << median(lt);
  RenderSettings balance = s;
  balance.mis.heuristic = MisHeuristic::Balance;
  RenderSession reference(scene, balance);
  for (int p = 0; p < 64; ++p) ASSERT_TRUE(reference.renderPass());
  EXPECT_NE(session.image().rgb, reference.image().rgb);
}

// Unbiased on every bundled scene: the variance-aware estimate agrees region by region with the
// balance heuristic's (other seeds), and with the path tracer's where it samples every path in a
// short render (the scenes' comments in bpt_agreement_test.cpp say where it does not: caustics,
// fog's spot, the door's gap, the point lamp of many-lights). Pixels that see an emitter or a delta
// surface directly are left out as there.
void expectAgreement(test::BundledGroup group) {
  test::expectBundledGroupAgreement(
      group, "variance-aware", [](RenderSettings& s) { s.mis.heuristic = MisHeuristic::VarianceAware; }, 701);
}

TEST(VarianceAwareMis, AgreesOnTheDiffuseScenes) { expectAgreement(test::BundledGroup::Diffuse); }

TEST(VarianceAwareMis, AgreesOnTheGlossyAndSpecularScenes) { expectAgreement(test::BundledGroup::GlossyAndSpecular); }

TEST(VarianceAwareMis, AgreesInMediaAndHardVisibility) { expectAgreement(test::BundledGroup::MediaAndHardVisibility); }

}  // namespace variance_aware_test
}  // namespace pathlab
