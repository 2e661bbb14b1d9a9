// The consistency check (issue 13, part 4; core/check/): the structural mask of the techniques
// able to sample a path against the densities' own verdict, the check's statistics on synthetic
// sums, and the whole check on renders: every bundled scene passes, a 5 % bias injected into one
// technique of length 2 or 3 is named (and only it), and over several seeds the check raises
// no more false alarms than its level allows, its z-scores calibrated.
#include "core/bpt/mis.h"
#include "core/check/check_report.h"
#include "core/check/merge_bias.h"
#include "core/render/render_session.h"
#include "core/sampling/technique_label.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/random_connections.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>

namespace pathlab {
namespace {

Scene bundled(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

// sampleableTechniques (from the vertices' delta flags) against techniquePossible on the full
// path densities, on random subpaths, for every connectable (s, t); and the mask is not trivial
// where delta vertices exist.
void checkMask(const Scene& scene, const std::string& name, int maxLength, bool expectRestricted) {
  const Camera camera(scene.cameraDesc(), 16, 12, LensOptions{});
  int compared = 0, restricted = 0;
  test::forEachConnection(scene, camera, maxLength, 300, Pcg32(2026, 7), [&](const MisPath& path, int s, int t) {
    const PathDensities d = pathDensities(scene, camera, path);
    uint64_t expected = 0;
    for (int sp = 0; sp < d.n; ++sp) expected |= techniquePossible(d, sp) ? uint64_t{1} << sp : 0;
    ASSERT_EQ(sampleableTechniques(path), expected) << name << " (" << s << "," << t << ")";
    EXPECT_TRUE((expected >> s) & 1u) << "a technique can sample the path it sampled";
    ++compared;
    restricted += expected != (uint64_t{1} << d.n) - 1 ? 1 : 0;
  });
  EXPECT_GT(compared, 300) << name;
  if (expectRestricted) EXPECT_GT(restricted, 20) << name;
  else EXPECT_EQ(restricted, 0) << name;
}

TEST(SampleableTechniques, MatchTheDensitiesOnTheCornellBox) { checkMask(bundled("cornell-box"), "cornell-box", 6, false); }
TEST(SampleableTechniques, MatchTheDensitiesOnTheCausticScene) { checkMask(bundled("caustic"), "caustic", 6, true); }
TEST(SampleableTechniques, MatchTheDensitiesWithDeltaLightAndGlass) {
  checkMask(Scene(test::deltaScene(test::DeltaLight::Point)), "delta scene", 6, true);
}

// Synthetic passes: technique i's and j's restricted estimates of one length, each pass a value
// per block. The comparison's mean difference and standard error are those of the per-pass
// differences; the culprit among three techniques is the only one named.
TEST(TechniqueCheck, PairStatisticsAreThoseOfThePerPassDifferences) {
  TechniqueCheck check(2, 1, 1, 1, [](Technique) { return true; });  // one block, techniques (0,2), (1,1)
  TechniqueCheck::PassSums sums(check);
  const Technique i{0, 2}, j{1, 1};
  const double ratios[2] = {1.0, 1.0};
  const double a[] = {1.0, 2.0, 4.0, 3.0}, b[] = {1.5, 1.0, 2.0, 2.5};
  for (int pass = 0; pass < 4; ++pass) {
    sums.add(i, Vec2(0.5f, 0.5f), static_cast<float>(a[pass]), 0b11, ratios);
    sums.add(j, Vec2(1.5f, 0.5f), static_cast<float>(b[pass]), 0b11, ratios);
    check.finishPass({&sums});
  }
  CheckOptions options;
  options.minPasses = 2, options.minNonzeroPasses = 2;
  const PairComparison c = comparePair(check, i, j, TechniqueCheck::wholeImage(1), options);
  ASSERT_TRUE(c.valid);
  // a and b land in the one block of two pixels: each pass's means are a / 2 and b / 2.
  double mean = 0.0, m2 = 0.0;
  for (int p = 0; p < 4; ++p) mean += (a[p] - b[p]) / 2.0 / 4.0;
  for (int p = 0; p < 4; ++p) m2 += std::pow((a[p] - b[p]) / 2.0 - mean, 2.0);
  const double sampleSe = std::sqrt(m2 / 3.0 / 4.0);
  EXPECT_NEAR(c.difference, mean, 1e-12);
  // The model variance (second moments: one sample per pixel, here the whole value in one
  // pixel) is at least the sample one here.
  EXPECT_GE(c.standardError, sampleSe - 1e-12);
  double ownA2 = 0.0, ownB2 = 0.0;
  for (int p = 0; p < 4; ++p) ownA2 += a[p] * a[p] / 4.0 / 4.0, ownB2 += b[p] * b[p] / 4.0 / 4.0;
  const double ma = (a[0] + a[1] + a[2] + a[3]) / 8.0, mb = (b[0] + b[1] + b[2] + b[3]) / 8.0;
  // With density ratios of one each technique's samples estimate the other's second moment as
  // its own: the model takes the larger for both.
  const double model = (std::max(ownA2, ownB2) - ma * ma / 2.0) + (std::max(ownA2, ownB2) - mb * mb / 2.0);
  EXPECT_NEAR(c.standardError, std::sqrt(std::max(model, m2 / 3.0) / 4.0), 1e-12);
}

TEST(TechniqueCheck, NamesTheOneTechniqueThatDisagreesWithTheOthers) {
  // Length 2: (0,3), (1,2), (2,1) estimate the same integral with noise; (1,2) is 5 % high.
  TechniqueCheck check(8, 8, 2, 2, [](Technique x) { return x.s + x.t == 3; });
  TechniqueCheck::PassSums sums(check);
  Pcg32 rng(5, 5);
  const double ratios[3] = {1.0, 1.0, 1.0};
  for (int pass = 0; pass < 400; ++pass) {
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x)
        for (int s = 0; s <= 2; ++s) {
          const float value = (s == 1 ? 1.05f : 1.f) * (0.5f + rng.next1D());
          sums.add(Technique{s, 3 - s}, Vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f), value, 0b111,
                   ratios);
        }
    check.finishPass({&sums});
  }
  const CheckReport report = checkReport(check);
  ASSERT_EQ(report.techniques.size(), 3u);
  EXPECT_EQ(report.techniques[0].status, CheckStatus::Agrees);
  EXPECT_EQ(report.techniques[1].status, CheckStatus::Disagrees);
  EXPECT_EQ(report.techniques[2].status, CheckStatus::Agrees);
  EXPECT_GT(report.techniques[1].z, 5.0);
}

TEST(TechniqueCheck, ComparesMergesWithTheConnectionsOfTheirLength) {
  // Length 2 with both families at two radii: C(0,3), C(1,2), C(2,1) and M(2,2) estimate the same
  // integral with noise. The connections' report judges the connections alone; the merge is
  // judged by its difference extrapolated to r -> 0 (merge_bias.h): a bias that halves with the
  // radius passes, one that stays 5 % high at both radii (a wrong merge) is named.
  for (const bool consistent : {true, false}) {
    std::vector<std::unique_ptr<TechniqueCheck>> checks;
    std::vector<MergeBiasLevel> levels;
    Pcg32 rng(5, 5);
    const double ratios[4] = {1.0, 1.0, 1.0, 1.0};  // by slot
    constexpr TechniqueFamilies kBoth = TechniqueFamilies::Connections | TechniqueFamilies::Merges;
    const TechniqueRange length2 = techniquesOfLength(2, kBoth);
    for (const double radius : {0.1, 0.05}) {
      checks.push_back(std::make_unique<TechniqueCheck>(8, 8, 2, 2, [](Technique x) { return x.length() == 2; }, kBoth));
      TechniqueCheck& check = *checks.back();
      TechniqueCheck::PassSums sums(check);
      const float mergeFactor = consistent ? 1.f + static_cast<float>(radius) : 1.05f;  // 10 %, 5 %, or 5 % twice
      for (int pass = 0; pass < 400; ++pass) {
        for (int y = 0; y < 8; ++y)
          for (int x = 0; x < 8; ++x)
            for (const Technique t : length2) {
              const float value = (t.isMerge() ? mergeFactor : 1.f) * (0.5f + rng.next1D());
              sums.add(t, Vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f), value, 0b1111, ratios);
            }
        check.finishPass({&sums});
      }
      levels.push_back(MergeBiasLevel{radius, &check});
    }
    const CheckReport report = checkReport(*checks.front());
    ASSERT_EQ(report.techniques.size(), 3u) << "the merge is not among the connections' verdicts";
    for (size_t i = 0; i < 3; ++i) EXPECT_EQ(report.techniques[i].status, CheckStatus::Agrees) << i;
    const MergeBiasReport merges = mergeBiasReport(levels);
    ASSERT_EQ(merges.merges.size(), 1u);
    const MergeVerdict& m = merges.merges[0];
    EXPECT_EQ(m.technique, Technique::merge(2, 2));
    EXPECT_EQ(m.status, consistent ? CheckStatus::Agrees : CheckStatus::Disagrees) << mergeBiasText(merges);
    if (!consistent) {
      EXPECT_GT(std::abs(m.z), 5.0) << mergeBiasText(merges);
    } else {
      EXPECT_TRUE(m.shrinking()) << mergeBiasText(merges);
    }
    EXPECT_NE(mergeBiasText(merges).find("M(2,2)"), std::string::npos);
  }
}

struct CheckRun {
  CheckReport report;
  Image image;
};

CheckRun runCheck(const Scene& scene, RenderSettings s, int passes) {
  s.integrator = IntegratorKind::Bpt;
  s.checkTechniques = true;
  RenderSession session(scene, s);
  for (int p = 0; p < passes; ++p) session.renderPass();
  return {checkReport(*session.techniqueCheck()), session.image()};
}

RenderSettings small(int width, int height, int maxLength, uint64_t seed) {
  RenderSettings s;
  s.width = width, s.height = height, s.maxLength = maxLength, s.seed = seed;
  return s;
}

std::string describe(const CheckReport& r) { return checkReportText(r); }

int compared(const CheckReport& r) {
  int n = 0;
  for (const TechniqueVerdict& v : r.techniques) n += (v.status == CheckStatus::Agrees || v.status == CheckStatus::Disagrees);
  return n;
}

// Every bundled scene passes, with the techniques compared that can be (on the caustic and lamp
// scenes the point light leaves s = 0 nothing to sample).
TEST(TechniqueCheckRender, PassesOnEveryBundledScene) {
  struct Case {
    const char* name;
    int minCompared;
  };
  for (const Case c : {Case{"cornell-box", 9}, Case{"veach-mis", 9}, Case{"caustic", 4}, Case{"bidir-lamp", 4}}) {
    const CheckRun run = runCheck(bundled(c.name), small(48, 48, 3, 11), 300);
    EXPECT_TRUE(run.report.agrees()) << c.name << "\n" << describe(run.report);
    EXPECT_GE(compared(run.report), c.minCompared) << c.name << "\n" << describe(run.report);
  }
}

// A 5 % bias in one technique of length 2, then of length 3, is named, and no other technique
// is; the image moves by exactly 5 % of that technique's weighted share (same samples).
TEST(TechniqueCheckRender, NamesAnInjectedBiasOfFivePercent) {
  const Scene scene = bundled("cornell-box");
  for (const Technique culprit : {Technique{1, 2}, Technique{2, 2}}) {
    RenderSettings s = small(64, 64, 3, 3);
    s.injectBias = BiasInjection{culprit.s, culprit.t, 1.05f};
    const CheckRun run = runCheck(scene, s, 900);
    for (const TechniqueVerdict& v : run.report.techniques)
      EXPECT_EQ(v.status == CheckStatus::Disagrees, v.technique == culprit)
          << "(" << v.technique.s << "," << v.technique.t << ") with (" << culprit.s << "," << culprit.t
          << ") biased\n" << describe(run.report);
  }
}

// In fog bpt's equiangular techniques E(1, k) are compared like the connections (issue 35): the
// fog lamp passes with E(1, 2) and E(1, 3) among the compared techniques, and a 10 % bias in E(1, 2)
// is named, and no other technique is.
TEST(TechniqueCheckRender, ComparesTheEquiangularTechniquesInFog) {
  const Scene scene = bundled("fog-lamp");
  auto verdictOf = [](const CheckReport& r, Technique x) -> const TechniqueVerdict* {
    for (const TechniqueVerdict& v : r.techniques)
      if (v.technique == x) return &v;
    return nullptr;
  };
  RenderSettings s = small(40, 30, 3, 21);
  s.mediumSampling = MediumSampling::Mis;
  const CheckRun clean = runCheck(scene, s, 400);
  EXPECT_TRUE(clean.report.agrees()) << describe(clean.report);
  for (const Technique e : {Technique::equiangular(2), Technique::equiangular(3)}) {
    const TechniqueVerdict* v = verdictOf(clean.report, e);
    ASSERT_NE(v, nullptr) << techniqueLabel(e) << " is not compared\n" << describe(clean.report);
    EXPECT_EQ(v->status, CheckStatus::Agrees) << describe(clean.report);
  }
  const Technique culprit = Technique::equiangular(2);
  s.injectBias = BiasInjection{culprit.s, culprit.t, 1.1f, TechniqueKind::Equiangular};
  const CheckRun biased = runCheck(scene, s, 400);
  for (const TechniqueVerdict& v : biased.report.techniques)
    EXPECT_EQ(v.status == CheckStatus::Disagrees, v.technique == culprit)
        << techniqueLabel(v.technique) << " with E(1,2) biased\n" << describe(biased.report);
}

TEST(TechniqueCheckRender, InjectedBiasMovesTheImageByTheTechniquesShare) {
  const Scene scene = bundled("cornell-box");
  RenderSettings s = small(32, 32, 3, 5);
  s.integrator = IntegratorKind::Bpt;
  s.pyramidLength = 3;
  RenderSession clean(scene, s);
  s.injectBias = BiasInjection{1, 2, 1.05f};
  RenderSession biased(scene, s);
  for (int p = 0; p < 8; ++p) clean.renderPass(), biased.renderPass();
  auto sum = [](const Image& img) {
    double total = 0.0;
    for (const float v : img.rgb) total += v;
    return total;
  };
  const double share = sum(clean.techniqueImage({1, 2}, false));
  ASSERT_GT(share, 0.0);
  EXPECT_NEAR(sum(biased.image()) - sum(clean.image()), 0.05 * share, 1e-4 * share);
}

// Over independent seeds: the check's verdicts (at most one false alarm in ten at level 0.01)
// and its z-scores: the whole-image pairwise z of agreeing techniques have a mean square near
// one or below (the standard error is deliberately conservative: the larger of two estimates).
TEST(TechniqueCheckRender, FalseAlarmsAndZScoresOverSeeds) {
  const Scene scene = bundled("cornell-box");
  int alarms = 0, count = 0;
  double z2 = 0.0;
  for (uint64_t seed = 100; seed < 110; ++seed) {
    const CheckRun run = runCheck(scene, small(32, 32, 3, seed), 200);
    alarms += run.report.agrees() ? 0 : 1;
    for (const TechniqueVerdict& v : run.report.techniques)
      if (v.status == CheckStatus::Agrees) z2 += v.wholeImageZ * v.wholeImageZ, ++count;
  }
  EXPECT_LE(alarms, 1);
  ASSERT_GT(count, 50);
  const double meanZ2 = z2 / count;
  EXPECT_GT(meanZ2, 0.1) << "standard errors far too large: the check would have no power";
  EXPECT_LT(meanZ2, 1.5) << "standard errors too small: false alarms";
}

}  // namespace
}  // namespace pathlab
