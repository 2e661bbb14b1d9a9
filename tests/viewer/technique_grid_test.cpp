// The technique grid's logic: presets give the sets they promise, the SPEC field takes what fits,
// toggles of a cell, a length or a column round-trip.
#include "ui/estimator/technique_grid.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

TEST(TechniqueGrid, PresetsEnableExactlyTheirTechniques) {
  const int K = 6;
  const TechniqueSet all = presetTechniques(TechniquePreset::All);
  const TechniqueSet pt = presetTechniques(TechniquePreset::PathTracing);
  const TechniqueSet lt = presetTechniques(TechniquePreset::LightTracing);
  const TechniqueSet one = presetTechniques(TechniquePreset::OneLength, 3);
  const TechniqueSet none = presetTechniques(TechniquePreset::Clear);
  for (const Technique x : techniquesUpTo(K)) {
    EXPECT_TRUE(all.contains(x));
    EXPECT_EQ(pt.contains(x), x.s <= 1) << x.s << "," << x.t;
    EXPECT_EQ(lt.contains(x), x.t == 1) << x.s << "," << x.t;
    EXPECT_EQ(one.contains(x), x.length() == 3) << x.s << "," << x.t;
    EXPECT_FALSE(none.contains(x));
  }
  EXPECT_TRUE(none.empty());
  // Path tracing and light tracing cover every length; one length leaves the others uncovered.
  EXPECT_TRUE(pt.uncoveredLengths(K).empty());
  EXPECT_TRUE(lt.uncoveredLengths(K).empty());
  EXPECT_EQ(one.uncoveredLengths(K), (std::vector<int>{1, 2, 4, 5, 6}));
  // The SPEC field's words for them.
  EXPECT_EQ(all.toString(), "all");
  EXPECT_EQ(pt.toString(), "s=0;s=1");
  EXPECT_EQ(lt.toString(), "t=1");
  EXPECT_EQ(one.toString(), "k=3");
}

TEST(TechniqueGrid, TogglesRoundTrip) {
  TechniqueSet set = TechniqueSet::all();
  set = toggleTechnique(set, 4, {2, 2});
  EXPECT_FALSE(set.contains(2, 2));
  EXPECT_EQ(set.count(4), TechniqueSet::all().count(4) - 1);
  set = toggleTechnique(set, 4, {2, 2});
  EXPECT_EQ(set, TechniqueSet::all());  // "all" again once everything is back on
  EXPECT_EQ(toggleTechnique(TechniqueSet(), 3, {1, 1}), TechniqueSet::parse("1,1"));
  EXPECT_TRUE(toggleTechnique(TechniqueSet::parse("1,1"), 3, {1, 1}).empty());
  // A length and a column: on when some of it is off, off when all of it is on.
  set = toggleLength(TechniqueSet::parse("1,2"), 4, 2);
  EXPECT_EQ(set, TechniqueSet::ofLength(2));
  EXPECT_TRUE(toggleLength(set, 4, 2).empty());
  set = toggleLightVertices(TechniqueSet::parse("1,2"), 4, 1);
  EXPECT_EQ(set, TechniqueSet::withS(1));  // a column switched on grows with the maximum
  EXPECT_EQ(toggleLightVertices(TechniqueSet::pathTracing(), 4, 1), TechniqueSet::withS(0));  // still a rule
  set = toggleLightVertices(TechniqueSet::all(), 3, 1);  // a hole in "all": listed up to the maximum
  EXPECT_EQ(set, TechniqueSet::parse("0,2;0,3;2,1;0,4;2,2;3,1"));
}

TEST(TechniqueGrid, AMergeTogglesBesideTheConnections) {
  // A merge cell switches that merge alone: "all" stays "all", and the merge survives the
  // connections being switched off and on around it.
  TechniqueSet set = toggleTechnique(TechniqueSet::all(), 4, Technique::merge(2, 3));
  EXPECT_EQ(set.toString(), "all;M2,3");
  set = toggleTechnique(set, 4, {1, 1});
  set = toggleTechnique(set, 4, {1, 1});
  EXPECT_EQ(set.toString(), "all;M2,3");
  set = toggleLength(set, 4, 3);
  EXPECT_TRUE(set.contains(Technique::merge(2, 3)));
  EXPECT_FALSE(set.contains(1, 3));
  set = toggleTechnique(toggleLength(set, 4, 3), 4, Technique::merge(2, 3));
  EXPECT_EQ(set, TechniqueSet::all());
  RenderSettings pt;
  pt.integrator = IntegratorKind::Pt;
  EXPECT_FALSE(techniqueShownEnabled(pt, Technique::merge(2, 2)));
  // The merge row's label and the "+merges (VCM)" button round-trip.
  TechniqueSet vcm = toggleAllMerges(TechniqueSet::all(), 4);
  EXPECT_EQ(vcm.toString(), "all;m=all");
  TechniqueSet row = toggleMergesOfLength(vcm, 4, 3);
  EXPECT_EQ(row.toString(), "all;m=2;m=4");
  EXPECT_EQ(toggleMergesOfLength(row, 4, 3).toString(), "all;m=all");  // compacted, as "all" is
  EXPECT_EQ(toggleAllMerges(vcm, 4), TechniqueSet::all());
  EXPECT_EQ(toggleAllMerges(row, 4).toString(), "all;m=all");
}

TEST(TechniqueGrid, TheSpecFieldTakesNothingOrASpecThatFits) {
  EXPECT_TRUE(parseTypedSpec(" ; ", 4).empty());
  EXPECT_EQ(parseTypedSpec("k=1", 4), TechniqueSet::parse("0,2;1,1"));
  EXPECT_THROW(parseTypedSpec("1;x", 4), std::invalid_argument);
  EXPECT_THROW(parseTypedSpec("3,3", 4), std::invalid_argument);  // length 5
  EXPECT_THROW(parseTypedSpec("s=6", 4), std::invalid_argument);  // nothing up to length 4
}

// The grid ticks what the integrator uses: the enabled set for bpt, its t = 1 part for lt, and
// for the path tracer its own techniques s <= 1 whatever the set.
TEST(TechniqueGrid, TicksWhatTheIntegratorUses) {
  RenderSettings s;
  s.maxLength = 3;
  s.techniques = TechniqueSet::parse("0,3;2,2");
  s.integrator = IntegratorKind::Bpt;
  EXPECT_TRUE(techniqueShownEnabled(s, {0, 3}));
  EXPECT_FALSE(techniqueShownEnabled(s, {1, 2}));
  s.integrator = IntegratorKind::Lt;
  EXPECT_FALSE(techniqueShownEnabled(s, {0, 3}));
  s.techniques = TechniqueSet::all();
  EXPECT_TRUE(techniqueShownEnabled(s, {3, 1}));
  EXPECT_FALSE(techniqueShownEnabled(s, {2, 2}));
  s.integrator = IntegratorKind::Pt;
  s.techniques = TechniqueSet::parse("2,2");
  for (const Technique x : techniquesUpTo(3)) EXPECT_EQ(techniqueShownEnabled(s, x), x.s <= 1) << x.s << "," << x.t;
}

TEST(TechniqueGrid, EmptySetMeansNothingToRender) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = presetTechniques(TechniquePreset::Clear);
  EXPECT_TRUE(noTechniqueEnabled(s));
  s.integrator = IntegratorKind::Pt;  // the path tracer ignores the set
  EXPECT_FALSE(noTechniqueEnabled(s));
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse("0,2");
  EXPECT_FALSE(noTechniqueEnabled(s));
  s.maxLength = 3;
  s.techniques = TechniqueSet::withS(4);  // none of length <= 3
  EXPECT_TRUE(noTechniqueEnabled(s));
}

}  // namespace
}  // namespace pathlab::ui
