// The estimator state the viewer's panels edit: the isolation kept once (mode and technique), a
// new maximum length keeps the settings renderable, presets, and what the renderer gets.
#include "ui/estimator/estimator_state.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

EstimatorState bidirectional(int maxLength = 10) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = maxLength;
  return EstimatorState::from(s);
}

TEST(EstimatorState, ModesIsolateTheOneRememberedTechnique) {
  EstimatorState e = bidirectional();
  EXPECT_EQ(e.mode, EstimatorMode::Combine);
  EXPECT_FALSE(renderSettings(e).isolate);
  EXPECT_TRUE(setIsolated(e, {2, 2}));
  EXPECT_FALSE(renderSettings(e).isolate);  // remembered while combining
  cycleMode(e);
  EXPECT_EQ(e.mode, EstimatorMode::IsolateWeighted);
  EXPECT_EQ(*renderSettings(e).isolate, (Isolation{2, 2, false}));
  cycleMode(e);
  EXPECT_EQ(*renderSettings(e).isolate, (Isolation{2, 2, true}));
  EXPECT_FALSE(setIsolated(e, {0, 12}));  // length 11 > 10: ignored
  EXPECT_FALSE(setIsolated(e, {0, 1}));
  EXPECT_EQ(e.isolated, (Technique{2, 2}));
  cycleMode(e);
  EXPECT_EQ(e.mode, EstimatorMode::Combine);
  EXPECT_FALSE(renderSettings(e).isolate);
  // A click on a pyramid thumbnail: that technique alone, bpt when the path tracer was on.
  e.settings.integrator = IntegratorKind::Pt;
  isolate(e, {1, 2}, true);
  EXPECT_EQ(e.settings.integrator, IntegratorKind::Bpt);
  EXPECT_EQ(*renderSettings(e).isolate, (Isolation{1, 2, true}));
  // Settings with an isolation become the mode and the technique, and come back out unchanged.
  RenderSettings s = renderSettings(e);
  s.isolate = Isolation{3, 1, false};
  e = EstimatorState::from(s);
  EXPECT_EQ(e.mode, EstimatorMode::IsolateWeighted);
  EXPECT_FALSE(e.settings.isolate);
  EXPECT_EQ(renderSettings(e), s);
}

TEST(EstimatorState, ShorterMaximumKeepsTheSettingsValid) {
  EstimatorState e = bidirectional(6);
  e.settings.techniques = TechniqueSet::parse("0,2;2,4;5,2");  // lengths 1, 5, 6
  e.isolated = {3, 3};                                           // length 5
  e.mode = EstimatorMode::IsolateWeighted;
  setMaxLength(e, 4);
  EXPECT_EQ(e.settings.techniques, TechniqueSet::parse("0,2"));
  EXPECT_EQ(e.isolated.s, 3);
  EXPECT_EQ(e.isolated.length(), 4);
  EXPECT_NO_THROW(validateSettings(renderSettings(e)));
  // Presets grow and shrink with the maximum.
  e.settings.techniques = TechniqueSet::pathTracing();
  setMaxLength(e, 2);
  EXPECT_EQ(e.settings.techniques, TechniqueSet::pathTracing());
  setMaxLength(e, 9);
  EXPECT_TRUE(e.settings.techniques.contains(1, 8));
  e.settings.techniques = TechniqueSet::all();
  setMaxLength(e, 1);
  setMaxLength(e, 12);
  EXPECT_EQ(e.settings.techniques, TechniqueSet::all());
  // s alone too long: the longest light-tracing technique.
  e.isolated = {7, 1};
  e.mode = EstimatorMode::IsolateUnweighted;
  setMaxLength(e, 3);
  EXPECT_EQ(*renderSettings(e).isolate, (Isolation{3, 1, true}));
  // Settings whose isolated technique is the default (1,2) at maximum length 1.
  RenderSettings one;
  one.maxLength = 1;
  EXPECT_EQ(EstimatorState::from(one).isolated.length(), 1);
}

TEST(EstimatorState, PresetsSetTheIsolationOrKeepTheTechnique) {
  EstimatorState e = bidirectional();
  setIsolated(e, {2, 3});
  e.mode = EstimatorMode::IsolateWeighted;
  NamedPreset p;
  p.techniques = TechniqueSet::lightTracing();
  p.maxLength = 6;
  applyPreset(e, p);
  EXPECT_EQ(e.mode, EstimatorMode::Combine);
  EXPECT_EQ(e.isolated, (Technique{2, 3}));  // kept for the isolate modes
  EXPECT_EQ(e.settings.techniques, TechniqueSet::lightTracing());
  EXPECT_EQ(e.settings.maxLength, 6);
  p.isolate = Isolation{4, 1, true};
  applyPreset(e, p);
  EXPECT_EQ(e.mode, EstimatorMode::IsolateUnweighted);
  EXPECT_EQ(e.isolated, (Technique{4, 1}));
}

TEST(EstimatorState, WarnsWhenTheWeightedIsolatedTechniqueIsOff) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::lightTracing();
  s.isolate = Isolation{1, 2, false};
  EXPECT_TRUE(isolatedTechniqueDisabled(s));
  s.isolate->unweighted = true;  // its own estimate does not depend on the set
  EXPECT_FALSE(isolatedTechniqueDisabled(s));
  s.isolate = Isolation{2, 1, false};
  EXPECT_FALSE(isolatedTechniqueDisabled(s));
}

TEST(EstimatorState, PathTracerGetsNoIsolationOrPyramid) {
  EstimatorState e = bidirectional();
  e.settings.integrator = IntegratorKind::Pt;
  e.mode = EstimatorMode::IsolateWeighted;
  e.settings.pyramidLength = 3;
  const RenderSettings r = renderSettings(e);
  EXPECT_FALSE(r.isolate);
  EXPECT_EQ(r.pyramidLength, 0);
  EXPECT_NO_THROW(validateSettings(r));
  e.settings.integrator = IntegratorKind::Bpt;
  EXPECT_EQ(renderSettings(e).pyramidLength, 3);
  EXPECT_TRUE(renderSettings(e).isolate);
}

TEST(EstimatorState, DescriptionNamesTheEstimator) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 5;
  s.isolate = Isolation{2, 2, true};
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, isolate (2,2) unweighted");
  s.isolate.reset();
  s.mis.heuristic = MisHeuristic::Power;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS power (beta 2)");
  s.techniques = TechniqueSet::parse("1,2;s=0;2,1;E1,2");  // every technique of length 2
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques s=0;k=2, MIS power (beta 2)");
  s.injectBias = BiasInjection{1, 2, 1.05f};
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques s=0;k=2, MIS power (beta 2), BIAS INJECTED: (1,2) x 1.05");
}

// bpt's equiangular techniques (issue 35): the two lanes of the fog preset say which is which.
TEST(EstimatorState, DescriptionNamesTheEquiangularTechniques) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 5;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS balance");
  s.mediumSampling = MediumSampling::Mis;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS balance, equiangular E(1,k) beside C(1,k)");
  s.mediumSampling = MediumSampling::Equiangular;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS balance, equiangular E(1,k) in place of C(1,k)");
  s.mediumSampling = MediumSampling::Distance;
  EXPECT_EQ(describe(s), "bpt, max length 5, techniques all, MIS balance, distance sampling alone in media (no E(1,k))");
}

// With merges the line names the radius, its schedule and where the camera subpath merges, so a
// screenshot of a ppm render says it is one (the integrator's radio says bpt).
TEST(EstimatorState, DescriptionNamesTheMergeRadiusAndSite) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 4;
  s.techniques = TechniqueSet::parse("all;m=all");
  s.mergeRadius = 0.01f;
  s.mergeRadiusAlpha = 0.5f;
  EXPECT_EQ(describe(s), "bpt, max length 4, techniques all;m=all, MIS balance, merging radius 0.01 alpha 0.5");
  s.techniques = TechniqueSet::parse("s=0;m=all");
  s.mergeSite = MergeSite::FirstNonSpecular;
  EXPECT_EQ(describe(s), "bpt, max length 4, techniques s=0;m=all, MIS balance, merging radius 0.01 alpha 0.5 at the "
                         "first non-specular camera vertex (ppm)");
  s.mergeNonCaustic = 0.1f;
  EXPECT_EQ(describe(s), "bpt, max length 4, techniques s=0;m=all, MIS balance, merging radius 0.01 alpha 0.5 at the "
                         "first non-specular camera vertex (ppm), non-caustic photons 0.1");
  s.techniques = TechniqueSet::all();  // no merge: nothing about merging
  EXPECT_EQ(describe(s), "bpt, max length 4, techniques all, MIS balance");
}

// Metropolis: what decides the chains, so that an A | B of two chain settings tells them apart.
TEST(EstimatorState, DescriptionNamesTheChainsSettings) {
  RenderSettings s;
  s.integrator = IntegratorKind::Mlt;
  s.maxLength = 4;
  EXPECT_EQ(describe(s), "mlt, max length 4, techniques all, MIS balance, mmlt chains 1000, large step 0.3, sigma 0.01, "
                         "bootstrap 100000");
  s.mlt.variant = MltVariant::PrimarySpace;
  s.mlt.directLength = 2;
  s.mlt.sigma = 0.05f;
  EXPECT_EQ(describe(s), "mlt, max length 4, techniques all, MIS balance, pss chains 1000, large step 0.3, sigma 0.05, "
                         "bootstrap 100000, up to 2 edges by BPT");
}

// Ctrl+digit S isolates (S, k + 1 - S) of the grid's chosen length: the seed's comparison of one
// length's techniques a key each; the isolate mode is kept, combining becomes the weighted share.
TEST(EstimatorState, DigitKeysIsolateTheTechniquesOfTheChosenLength) {
  EstimatorState e;
  e.settings.integrator = IntegratorKind::Pt;
  e.settings.maxLength = 5;
  EXPECT_TRUE(isolateOfChosenLength(e, 2, 0));
  EXPECT_EQ(e.isolated, (Technique{0, 3}));
  EXPECT_EQ(e.mode, EstimatorMode::IsolateWeighted);
  EXPECT_EQ(e.settings.integrator, IntegratorKind::Bpt);
  e.mode = EstimatorMode::IsolateUnweighted;
  EXPECT_TRUE(isolateOfChosenLength(e, 2, 2));
  EXPECT_EQ(e.isolated, (Technique{2, 1}));
  EXPECT_EQ(e.mode, EstimatorMode::IsolateUnweighted);
  EXPECT_FALSE(isolateOfChosenLength(e, 2, 3));  // no (3,0)
  EXPECT_EQ(e.isolated, (Technique{2, 1}));
  EXPECT_TRUE(isolateOfChosenLength(e, 9, 5));  // the length is clamped to the maximum, 5
  EXPECT_EQ(e.isolated, (Technique{5, 1}));
}

// Issue 14's honest labels: what each integrator really does, not the bidirectional settings it
// ignores (the path tracer's power heuristic; light tracing's t = 1 techniques).
TEST(EstimatorState, DescriptionSaysWhatPathAndLightTracingUse) {
  RenderSettings s;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Pt;
  s.mis.heuristic = MisHeuristic::Balance;
  EXPECT_EQ(describe(s), "pt, max length 4, light sample + BSDF sampling, MIS power (beta 2)");
  s.integrator = IntegratorKind::Lt;
  EXPECT_EQ(describe(s), "lt, max length 4, techniques t=1, one technique a length (weight 1)");
  s.techniques = TechniqueSet::parse("k=2");
  EXPECT_EQ(describe(s), "lt, max length 4, techniques 2,1, one technique a length (weight 1)");
}

// Metropolis (issue 33): the renderer gets the set's connections alone, and nothing that needs a
// sample's every technique at its pixel, while the state keeps them for the other integrators.
TEST(EstimatorState, MetropolisGetsTheConnectionsAndNoPerTechniqueOutputs) {
  EstimatorState e = bidirectional(6);
  e.settings.techniques = TechniqueSet::parse("all;m=all");
  e.settings.pyramidLength = 3;
  e.settings.techniqueMaps = true;
  e.settings.checkTechniques = true;
  e.settings.injectBias = BiasInjection{1, 2, 2.f};
  EXPECT_TRUE(setIsolated(e, {2, 2}));
  cycleMode(e);
  e.settings.integrator = IntegratorKind::Mlt;
  const RenderSettings s = renderSettings(e);
  EXPECT_NO_THROW(validateSettings(s));
  EXPECT_EQ(s.techniques.families(), TechniqueFamilies::Connections | TechniqueFamilies::Equiangular);  // "all"
  EXPECT_TRUE(s.techniques.containsAllUpTo(6));
  EXPECT_FALSE(s.isolate);
  EXPECT_EQ(s.pyramidLength, 0);
  EXPECT_FALSE(s.techniqueMaps || s.checkTechniques || s.injectBias);
  e.settings.integrator = IntegratorKind::Bpt;
  EXPECT_EQ(renderSettings(e).techniques.families(), TechniqueFamilies::All);
  EXPECT_TRUE(renderSettings(e).isolate);
}

}  // namespace
}  // namespace pathlab::ui
