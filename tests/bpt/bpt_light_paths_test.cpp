// Fewer light subpaths than camera samples (--light-paths F, core/bpt/light_paths.h): a camera
// sample walks one with probability F; the techniques that need it count F samples in every MIS
// weight and are divided by F. Tested: the table of counts; the walk's frequency; the weights'
// partition of unity on every path (checkMis); the estimate unbiased on every bundled scene (it
// agrees region by region with F = 1 and with the path tracer where that samples every path); and
// F < 1 really walks fewer light subpaths and changes the image.
#include "core/bpt/light_paths.h"
#include "core/render/render_session.h"
#include "core/render/sample_inspection.h"
#include "tests/support/agreement.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace light_paths_test {

TEST(LightPaths, CountsTheTechniquesThatWalkTheLightSubpath) {
  const std::vector<float> counts = lightPathCounts(4, 0.25f);
  ASSERT_EQ(counts.size(), Technique::countUpTo(4));
  for (size_t i = 0; i < counts.size(); ++i) {
    const Technique x = Technique::fromIndex(i);
    // s = 0 hits the light, s = 1 with t >= 2 samples its light point afresh: no light walk.
    const bool walks = !x.isMerge() && (x.t == 1 || x.s >= 2);
    EXPECT_EQ(counts[i], walks ? 0.25f : 1.f) << "(" << x.s << "," << x.t << ")";
  }
}

TEST(LightPaths, WalksWithTheProbabilityAsked) {
  for (const float f : {0.01f, 0.3f, 0.75f}) {
    const int n = 200000;
    int walked = 0;
    for (int i = 0; i < n; ++i) walked += walksLightSubpath(mixBits(static_cast<uint64_t>(i) + 12345), f) ? 1 : 0;
    const double sigma = std::sqrt(n * f * (1.0 - f));
    EXPECT_NEAR(walked, n * f, 4.0 * sigma) << "F " << f;
  }
  EXPECT_TRUE(walksLightSubpath(7, 1.f));
}


RenderSettings boxSettings(float lightPaths) {
  RenderSettings s;
  s.width = 24;
  s.height = 24;
  s.maxLength = 5;
  s.integrator = IntegratorKind::Bpt;
  s.lightPaths = lightPaths;
  return s;
}

TEST(LightPaths, EveryPathsWeightsSumToOne) {
  const Scene scene = test::bundledScene("cornell-spheres");
  for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    RenderSettings s = boxSettings(0.3f);
    s.mis.heuristic = h;
    s.checkMis = true;
    RenderSession session(scene, s);
    for (int p = 0; p < 4; ++p) ASSERT_TRUE(session.renderPass());
    EXPECT_GT(session.counters().misPartitionChecks, 1000u);
    EXPECT_EQ(session.counters().misPartitionFailures, 0u) << misHeuristicName(h);
  }
}

TEST(LightPaths, FewerLightWalksAndAnotherImage) {
  const Scene scene = test::bundledScene("cornell-box");
  RenderSession all(scene, boxSettings(1.f)), some(scene, boxSettings(0.25f));
  for (int p = 0; p < 8; ++p) ASSERT_TRUE(all.renderPass() && some.renderPass());
  const double ratio = static_cast<double>(some.counters().lightWalk.rays) / static_cast<double>(all.counters().lightWalk.rays);
  EXPECT_NEAR(ratio, 0.25, 0.02);
  EXPECT_NE(all.image().rgb, some.image().rgb);
}

// The counts are in the weights the image gets (with 1 / F on the contributions any partition of
// unity stays unbiased, so only the weights themselves show them): every contributed record's
// weight is its path's balance weight with F samples for the light-walk techniques, as the
// inspector lists it, and not the weight with one sample each.
TEST(LightPaths, TheWeightsCountTheLightPaths) {
  const Scene scene = test::bundledScene("cornell-box");
  const RenderSession session(scene, boxSettings(0.2f));
  int checked = 0, differs = 0;
  for (int x = 4; x < 24; x += 5)
    for (uint64_t sample = 0; sample < 24; ++sample) {
      const SampleInspection in = inspectSample(session, x, 12, sample);
      for (size_t i = 0; i < in.trace.records.size(); ++i) {
        const TechniqueResult& r = in.trace.records[i];
        if (r.outcome != TechniqueOutcome::Contributed || i >= in.trace.onPath.size()) continue;
        const std::vector<TechniqueOnPath>& every = in.trace.onPath[i];
        const TechniqueOnPath& own = every[static_cast<size_t>(r.technique().slot())];
        EXPECT_NEAR(r.weight, own.balance, 1e-5 * std::max(1.0, own.balance)) << "(" << r.s << "," << r.t << ")";
        // The balance weight with one sample each, from the same densities.
        double sum = 0.0;
        for (const TechniqueOnPath& y : every)
          if (y.counted && y.enabled) sum += y.pdfA;
        const double uncounted = sum > 0.0 ? own.pdfA / sum : 0.0;
        ++checked;
        differs += std::abs(uncounted - own.balance) > 1e-3 ? 1 : 0;
      }
    }
  EXPECT_GT(checked, 100);
  EXPECT_GT(differs, checked / 4);
}

// Unbiased on every bundled scene, as bpt_variance_aware_test.cpp tests variance-aware MIS: F = 0.25
// against F = 1 (another seed) everywhere, and against the path tracer where it samples every path
// in a short render (test::expectBundledAgreement).
void expectAgreement(const test::BundledCase& c) {
  test::expectBundledAgreement(c, "light-paths 0.25", [](RenderSettings& s) { s.lightPaths = 0.25f; }, 811);
}

TEST(LightPaths, AgreesOnTheDiffuseScenes) {
  expectAgreement({"cornell-box", 16, 16, 8, 256, 768});
  expectAgreement({"bidir-lamp", 15, 15, 8, 256, 768});
  expectAgreement({"environment", 16, 12, 6, 256, 2048});
  expectAgreement({"isometric", 16, 16, 6, 256, 512});
}

TEST(LightPaths, AgreesOnTheGlossyAndSpecularScenes) {
  expectAgreement({"cornell-spheres", 16, 16, 8, 512, 3072});
  expectAgreement({"veach-mis", 24, 16, 8, 512, 0});
  expectAgreement({"caustic", 16, 16, 8, 1536, 0, 2});
}

TEST(LightPaths, AgreesInMediaAndHardVisibility) {
  expectAgreement({"fog", 16, 16, 6, 512, 0});
  expectAgreement({"fog-lamp", 16, 12, 6, 256, 0});
  expectAgreement({"door-ajar", 16, 12, 8, 4096, 0, 2});  // light tracing carries the gap's light: more passes
  expectAgreement({"many-lights", 15, 10, 6, 1024, 0, 2});
}

}  // namespace light_paths_test
}  // namespace pathlab
