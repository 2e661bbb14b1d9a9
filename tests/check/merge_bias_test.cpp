// The consistency check of the merges (issue 32; core/check/merge_bias.h): the extrapolation to
// r -> 0 on exact polynomials, and on renders of vcm at a ladder of radii: a consistent merge
// passes although its bias at the largest radius is significant (a check at one radius would call
// it wrong), and a merge with its normalisation doubled is named, and nothing else is.
#include "core/check/check_json.h"
#include "core/check/merge_bias.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <memory>

namespace pathlab {
namespace {

Scene mergeBiasScene(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

TEST(MergeBias, ExtrapolationRecoversTheInterceptOfPolynomialsInR) {
  // D(r) = a + b r + c r^2 exactly at three radii, a + b r at two: the fit returns a.
  auto point = [](double r, double d, double se) { return RadiusDifference{r, d, se, 1.0, true}; };
  const double a = 0.3, b = -2.0, c = 40.0;
  auto quadratic = [&](double r) { return a + b * r + c * r * r; };
  const std::vector<RadiusDifference> three{point(0.1, quadratic(0.1), 0.01), point(0.05, quadratic(0.05), 0.02),
                                            point(0.025, quadratic(0.025), 0.04)};
  const RadiusFit fit3 = extrapolateToZeroRadius(three);
  ASSERT_TRUE(fit3.valid);
  EXPECT_EQ(fit3.degree, 2);
  EXPECT_NEAR(fit3.atZero, a, 1e-9);
  // Lagrange at 0 for radii 1, 1/2, 1/4 (units of the largest): weights 1/3, -2, 8/3.
  EXPECT_NEAR(fit3.standardError, std::sqrt(std::pow(0.01 / 3, 2) + std::pow(2 * 0.02, 2) + std::pow(8.0 / 3 * 0.04, 2)), 1e-12);
  const std::vector<RadiusDifference> two{point(0.1, a + b * 0.1, 0.01), point(0.05, a + b * 0.05, 0.01)};
  const RadiusFit fit2 = extrapolateToZeroRadius(two);
  ASSERT_TRUE(fit2.valid);
  EXPECT_EQ(fit2.degree, 1);
  EXPECT_NEAR(fit2.atZero, a, 1e-12);
  // An invalid point is left out; one valid point cannot be extrapolated.
  std::vector<RadiusDifference> one = two;
  one[1].valid = false;
  EXPECT_FALSE(extrapolateToZeroRadius(one).valid);
}

struct LadderRun {
  std::vector<std::unique_ptr<RenderSession>> sessions;
  std::vector<MergeBiasLevel> levels;
  MergeBiasReport merges;
  CheckReport atLargestRadius;  // the connections' check at the largest radius
};

// vcm rendered at radii r, r/2, r/4 (alpha = 1), each with its own seed, as `pathlab check` does.
LadderRun runLadder(const Scene& scene, RenderSettings s, int passes) {
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse("all;m=all");
  s.checkTechniques = true;
  s.mergeRadiusAlpha = 1.f;
  LadderRun run;
  const float r = *s.mergeRadius;
  for (int level = 0; level < 3; ++level) {
    RenderSettings l = s;
    l.mergeRadius = r / static_cast<float>(1 << level);
    l.seed = s.seed + static_cast<uint64_t>(level);
    run.sessions.push_back(std::make_unique<RenderSession>(scene, l));
    for (int p = 0; p < passes; ++p) run.sessions.back()->renderPass();
    run.levels.push_back(MergeBiasLevel{*l.mergeRadius, run.sessions.back()->techniqueCheck()});
  }
  run.merges = mergeBiasReport(run.levels);
  run.atLargestRadius = checkReport(*run.levels.front().check);
  return run;
}

RenderSettings mergeCheckSettings(uint64_t seed) {
  RenderSettings s;
  s.width = 48, s.height = 48, s.maxLength = 3, s.seed = seed;
  s.mergeRadius = 0.08f;
  s.mergeNonCaustic = 1.f;  // every light vertex: the check's power against the radius, as published
  return s;
}

std::string describeLadder(const LadderRun& run) {
  return checkReportText(run.atLargestRadius) + "\n" + mergeBiasText(run.merges);
}

// Every merge of lengths 2 and 3 is compared and consistent; the connections agree; and at the
// largest radius the bias of some merge is significant on its own (|z| > 4 over the whole image
// against its partner): a check at one radius would call it wrong, the extrapolation does not.
TEST(MergeBiasRender, VcmIsConsistentOnTheCornellBox) {
  const LadderRun run = runLadder(mergeBiasScene("cornell-box"), mergeCheckSettings(21), 200);
  ASSERT_EQ(run.merges.merges.size(), 3u);
  for (const MergeVerdict& v : run.merges.merges)
    EXPECT_EQ(v.status, CheckStatus::Agrees) << describeLadder(run);
  for (const TechniqueVerdict& v : run.atLargestRadius.techniques)
    EXPECT_NE(v.status, CheckStatus::Disagrees) << describeLadder(run);
  // The whole image's difference at the largest radius alone, in standard errors.
  double biggestZ = 0.0;
  for (const MergeVerdict& v : run.merges.merges)
    if (!v.wholeImage.empty() && v.wholeImage[0].valid)
      biggestZ = std::max(biggestZ, std::abs(v.wholeImage[0].difference / v.wholeImage[0].standardError));
  EXPECT_GT(biggestZ, 4.0) << "no merge is visibly biased at the largest radius: the test shows nothing\n"
                           << describeLadder(run);
  const nlohmann::json json = checkJson(run.atLargestRadius, &run.merges);
  EXPECT_EQ(json["merges"]["techniques"].size(), 3u);
  EXPECT_EQ(json["merges"]["techniques"][0]["wholeImage"].size(), 3u);
  EXPECT_EQ(json["merges"]["radii"][1], 0.04f);
}

// M(2,2) with its density estimate's normalisation doubled (1 / (pi r^2 N) taken twice) keeps a
// difference of the size of its estimate at every radius: named, and no other merge is.
TEST(MergeBiasRender, NamesAMergeWithItsNormalisationDoubled) {
  RenderSettings s = mergeCheckSettings(31);
  const Technique culprit = Technique::merge(2, 2);
  s.injectBias = BiasInjection{culprit.s, culprit.t, 2.f, TechniqueKind::Merge};
  const LadderRun run = runLadder(mergeBiasScene("cornell-box"), s, 120);
  ASSERT_EQ(run.merges.merges.size(), 3u);
  for (const MergeVerdict& v : run.merges.merges)
    EXPECT_EQ(v.status == CheckStatus::Disagrees, v.technique == culprit) << describeLadder(run);
  EXPECT_NE(mergeBiasText(run.merges).find("does not vanish"), std::string::npos);
}

}  // namespace
}  // namespace pathlab
