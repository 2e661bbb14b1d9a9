// The technique grid's logic: presets give the SPECs they promise, toggles and a new maximum
// length keep the settings renderable, the path tracer gets no isolation or pyramid.
#include "ui/technique_grid.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

TechniqueSet setOf(TechniquePreset preset, int maxLength, int length = 1) {
  return parseOrEmpty(presetSpec(preset, length), maxLength);
}

TEST(TechniqueGrid, PresetsEnableExactlyTheirTechniques) {
  const int K = 6;
  const TechniqueSet all = setOf(TechniquePreset::All, K), pt = setOf(TechniquePreset::PathTracing, K),
                     lt = setOf(TechniquePreset::LightTracing, K), one = setOf(TechniquePreset::OneLength, K, 3),
                     none = setOf(TechniquePreset::Clear, K);
  for (int k = 1; k <= K; ++k)
    for (int s = 0; s <= k; ++s) {
      const int t = k + 1 - s;
      EXPECT_TRUE(all.contains(s, t));
      EXPECT_EQ(pt.contains(s, t), s <= 1) << s << "," << t;
      EXPECT_EQ(lt.contains(s, t), t == 1) << s << "," << t;
      EXPECT_EQ(one.contains(s, t), k == 3) << s << "," << t;
      EXPECT_FALSE(none.contains(s, t));
    }
  EXPECT_EQ(none.size(), 0);
  // Path tracing and light tracing cover every length; one length leaves the others uncovered.
  EXPECT_TRUE(pt.uncoveredLengths().empty());
  EXPECT_TRUE(lt.uncoveredLengths().empty());
  EXPECT_EQ(one.uncoveredLengths(), (std::vector<int>{1, 2, 4, 5, 6}));
}

TEST(TechniqueGrid, ToggleRoundTripsThroughTheSpec) {
  std::string spec = "all";
  spec = toggleTechnique(spec, 4, 2, 2);
  TechniqueSet set = TechniqueSet::parse(spec, 4);
  EXPECT_FALSE(set.contains(2, 2));
  EXPECT_EQ(set.size(), TechniqueSet::all(4).size() - 1);
  spec = toggleTechnique(spec, 4, 2, 2);
  EXPECT_EQ(spec, "all");  // compact again once everything is back on
  EXPECT_EQ(toggleTechnique("", 3, 1, 1), "1,1");
  EXPECT_EQ(toggleTechnique("1,1", 3, 1, 1), "");
}

TEST(TechniqueGrid, EmptySetMeansNothingToRender) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = presetSpec(TechniquePreset::Clear);
  EXPECT_TRUE(noTechniqueEnabled(s));
  s.integrator = IntegratorKind::Pt;  // the path tracer ignores the set
  EXPECT_FALSE(noTechniqueEnabled(s));
  s.integrator = IntegratorKind::Bpt;
  s.techniques = "0,2";
  EXPECT_FALSE(noTechniqueEnabled(s));
}

TEST(TechniqueGrid, ABadSpecNeverThrowsOutOfTheEdits) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = "1;x";
  EXPECT_FALSE(noTechniqueEnabled(s));  // the renderer refuses it, with its message
  EXPECT_NO_THROW(setMaxLength(s, 3));
  EXPECT_EQ(s.techniques, "1;x");
  EXPECT_THROW(validateSettings(s), std::invalid_argument);
}

TEST(TechniqueGrid, ModesSetAndDropTheIsolation) {
  RenderSettings s;
  EXPECT_EQ(modeOf(s), EstimatorMode::Combine);
  setMode(s, EstimatorMode::IsolateUnweighted, 2, 2);
  ASSERT_TRUE(s.isolate);
  EXPECT_EQ(*s.isolate, (Isolation{2, 2, true}));
  EXPECT_EQ(modeOf(s), EstimatorMode::IsolateUnweighted);
  setMode(s, EstimatorMode::IsolateWeighted, 1, 2);
  EXPECT_EQ(*s.isolate, (Isolation{1, 2, false}));
  setMode(s, EstimatorMode::Combine, 1, 2);
  EXPECT_FALSE(s.isolate);
}

TEST(TechniqueGrid, ShorterMaximumKeepsTheSettingsValid) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 6;
  s.techniques = "0,2;2,4;5,2";  // lengths 1, 5, 6
  s.isolate = Isolation{3, 3, false};  // length 5
  setMaxLength(s, 4);
  EXPECT_EQ(s.techniques, "0,2");
  ASSERT_TRUE(s.isolate);
  EXPECT_EQ(s.isolate->s, 3);
  EXPECT_EQ(s.isolate->s + s.isolate->t - 1, 4);
  EXPECT_NO_THROW(validateSettings(s));
  // Presets grow and shrink with the maximum.
  s.techniques = "s=0;s=1";
  setMaxLength(s, 2);
  EXPECT_EQ(s.techniques, "s=0;s=1");
  setMaxLength(s, 9);
  EXPECT_TRUE(TechniqueSet::parse(s.techniques, 9).contains(1, 8));
  // s alone too long: the longest light-tracing technique.
  s.isolate = Isolation{7, 1, true};
  setMaxLength(s, 3);
  EXPECT_EQ(*s.isolate, (Isolation{3, 1, true}));
}

TEST(TechniqueGrid, WarnsWhenTheWeightedIsolatedTechniqueIsOff) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = "t=1";
  s.isolate = Isolation{1, 2, false};
  EXPECT_TRUE(isolatedTechniqueDisabled(s));
  s.isolate->unweighted = true;  // its own estimate does not depend on the set
  EXPECT_FALSE(isolatedTechniqueDisabled(s));
  s.isolate = Isolation{2, 1, false};
  EXPECT_FALSE(isolatedTechniqueDisabled(s));
}

TEST(TechniqueGrid, PathTracerGetsNoIsolationOrPyramid) {
  RenderSettings s;
  s.integrator = IntegratorKind::Pt;
  s.isolate = Isolation{1, 2, false};
  s.pyramidLength = 3;
  const RenderSettings e = effectiveSettings(s);
  EXPECT_FALSE(e.isolate);
  EXPECT_EQ(e.pyramidLength, 0);
  EXPECT_NO_THROW(validateSettings(e));
  s.integrator = IntegratorKind::Bpt;
  EXPECT_EQ(effectiveSettings(s), s);
}

TEST(TechniqueGrid, DescriptionNamesTheEstimator) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 5;
  s.isolate = Isolation{2, 2, true};
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, isolate (2,2) unweighted");
  s.isolate.reset();
  s.mis.heuristic = MisHeuristic::Power;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS power (beta 2)");
}

}  // namespace
}  // namespace pathlab::ui
