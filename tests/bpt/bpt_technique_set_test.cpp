// Technique and TechniqueSet: the one triangular index, the SPEC parser and its canonical printing,
// equality of sets however they are spelled, and a set that does not change with the maximum length.
#include "core/bpt/technique_set.h"
#include "core/render/render_settings.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace pathlab {
namespace {

TEST(Technique, OneTriangularIndexInTheOrderOfTheGrid) {
  EXPECT_EQ((Technique{0, 2}.index()), 0u);
  EXPECT_EQ((Technique{1, 1}.index()), 1u);
  EXPECT_EQ((Technique{0, 3}.index()), 2u);
  EXPECT_EQ((Technique{2, 1}.index()), 4u);
  EXPECT_EQ((Technique{0, 4}.index()), 5u);
  EXPECT_EQ(Technique::countUpTo(4), 2u + 3u + 4u + 5u);
  EXPECT_EQ((Technique{3, 3}.length()), 5);
  EXPECT_FALSE((Technique{0, 1}.valid()));
  EXPECT_FALSE((Technique{1, 0}.valid()));
  size_t i = 0;
  for (const Technique x : techniquesUpTo(60)) {
    ASSERT_EQ(x.index(), i) << x.s << "," << x.t;
    ASSERT_EQ(Technique::fromIndex(i), x);
    ++i;
  }
  EXPECT_EQ(i, Technique::countUpTo(60));
  std::vector<Technique> row(techniquesOfLength(3).begin(), techniquesOfLength(3).end());
  EXPECT_EQ(row, (std::vector<Technique>{{0, 4}, {1, 3}, {2, 2}, {3, 1}}));
  EXPECT_EQ(techniquesUpTo(0).begin(), techniquesUpTo(0).end());
}

TEST(BptTechniqueSet, AllHasEveryTechniqueOfEveryLength) {
  const TechniqueSet set = TechniqueSet::all();
  EXPECT_EQ(set.count(4), 2 + 3 + 4 + 5);
  EXPECT_TRUE(set.contains(0, 2));
  EXPECT_TRUE(set.contains(4, 1));
  EXPECT_TRUE(set.contains(300, 200));
  EXPECT_FALSE(set.contains(1, 0));  // t >= 1
  EXPECT_FALSE(set.contains(0, 1));  // length 0
  EXPECT_TRUE(set.uncoveredLengths(4).empty());
  EXPECT_TRUE(set.containsAllUpTo(4));
  EXPECT_TRUE(TechniqueSet().empty());
  EXPECT_FALSE(TechniqueSet().anyUpTo(4));
}

TEST(BptTechniqueSet, ParsesEveryItemKind) {
  const TechniqueSet set = TechniqueSet::parse(" 1,2 ; s=0;t=1; k=4");
  EXPECT_TRUE(set.contains(1, 2));
  for (int t = 2; t <= 60; ++t) EXPECT_TRUE(set.contains(0, t));  // s=0 at every length
  for (int s = 1; s <= 60; ++s) EXPECT_TRUE(set.contains(s, 1));  // t=1 at every length
  for (const Technique x : techniquesOfLength(4)) EXPECT_TRUE(set.contains(x));
  EXPECT_FALSE(set.contains(2, 2));
  EXPECT_FALSE(set.contains(1, 5));  // k=4 is that length only
  EXPECT_EQ(TechniqueSet::parse("all"), TechniqueSet::all());
  EXPECT_EQ(TechniqueSet::parse("s=0;s=1"), TechniqueSet::pathTracing());
  EXPECT_EQ(TechniqueSet::parse("t=1"), TechniqueSet::lightTracing());
  TechniqueSet manual;
  manual.enable({2, 2});
  manual.disable({2, 2}, 3);
  EXPECT_TRUE(manual.empty());
}

TEST(BptTechniqueSet, EqualSetsCompareEqualHoweverSpelled) {
  EXPECT_EQ(TechniqueSet::parse("k=1"), TechniqueSet::parse("0,2;1,1"));
  EXPECT_EQ(TechniqueSet::parse("s=0;k=2"), TechniqueSet::parse("1,2; s=0 ;2,1"));
  EXPECT_EQ(TechniqueSet::parse("all;s=3;1,1"), TechniqueSet::all());
  EXPECT_EQ(TechniqueSet::parse("t=1;1,1;2,1"), TechniqueSet::lightTracing());
  EXPECT_EQ(TechniqueSet::parse("s=1;s=0"), TechniqueSet::parse("s=0;s=1;0,7"));
  // Equal up to length 3 is not equal: they differ once the maximum grows.
  EXPECT_NE(TechniqueSet::pathTracing().upTo(3), TechniqueSet::pathTracing());
  EXPECT_EQ(TechniqueSet::pathTracing().upTo(3).count(3), 6);
  // So RenderSettings with such sets are equal, and a renderer starts no new generation for them
  // (tests/render/progressive_renderer_test.cpp).
  RenderSettings a, b;
  a.techniques = TechniqueSet::parse("k=1");
  b.techniques = TechniqueSet::parse("0,2;1,1");
  EXPECT_EQ(a, b);
}

TEST(BptTechniqueSet, CanonicalSpecRoundTrips) {
  const std::pair<const char*, const char*> canonical[] = {
      {"all", "all"},           {"k=2;0,2;1,1", "k=1;k=2"},  {"s=1;s=0", "s=0;s=1"},    {"all;k=2", "all"},
      {"s=0;k=2", "s=0;k=2"},   {"2,1;t=1", "t=1"},          {"3,1;0,2", "0,2;3,1"},    {"t=2;s=4;1,1", "s=4;t=2;k=1"},
      {"1,2;k=3", "1,2;k=3"},   {"s=0;1,2", "s=0;1,2"},      {"t=1;k=2", "t=1;k=2"},
  };
  for (const auto& [spec, printed] : canonical) {
    const TechniqueSet set = TechniqueSet::parse(spec);
    EXPECT_EQ(set.toString(), printed) << spec;
    EXPECT_EQ(TechniqueSet::parse(set.toString()), set) << spec;
  }
  EXPECT_EQ(TechniqueSet().toString(), "");
  // Random unions of rules and listed techniques, with holes clicked into them.
  std::mt19937 rng(11);
  auto pick = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
  for (int trial = 0; trial < 500; ++trial) {
    TechniqueSet set;
    for (int i = pick(3); i > 0; --i) set |= TechniqueSet::withS(pick(6));
    for (int i = pick(3); i > 0; --i) set |= TechniqueSet::withT(1 + pick(6));
    if (pick(4) == 0) set |= TechniqueSet::ofLength(1 + pick(6));
    for (int i = pick(6); i > 0; --i) {
      const int k = 1 + pick(8), s = pick(k + 1);
      set.enable({s, k + 1 - s});
    }
    if (pick(3) == 0) {
      const int k = 1 + pick(6), s = pick(k + 1);
      set.disable({s, k + 1 - s}, 7);
    }
    if (set.empty()) continue;
    EXPECT_EQ(TechniqueSet::parse(set.toString()), set) << set.toString();
  }
}

TEST(BptTechniqueSet, TheMaximumLengthDoesNotChangeTheSet) {
  // Rules hold at every length; listed techniques stay what they were.
  const TechniqueSet pt = TechniqueSet::pathTracing();
  EXPECT_TRUE(pt.contains(1, 40));
  EXPECT_TRUE(pt.uncoveredLengths(50).empty());
  const TechniqueSet listed = TechniqueSet::parse("0,2;2,4;5,2");  // lengths 1, 5, 6
  EXPECT_EQ(listed.fittedTo(4), TechniqueSet::parse("0,2"));
  EXPECT_EQ(listed.fittedTo(9), listed);
  EXPECT_EQ((TechniqueSet::parse("s=2;2,4")).fittedTo(3), TechniqueSet::withS(2));  // (2,4) is on the s = 2 line
  EXPECT_NO_THROW(listed.checkFits(6));
  try {
    listed.checkFits(5);
    ADD_FAILURE() << "(5,2) does not fit length 5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("(5,2)"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(TechniqueSet::all().checkFits(1));
  EXPECT_THROW(TechniqueSet::withS(5).checkFits(4), std::invalid_argument);  // nothing to render
  EXPECT_THROW(TechniqueSet().checkFits(4), std::invalid_argument);
  EXPECT_FALSE(TechniqueSet::withS(5).anyUpTo(4));
  EXPECT_TRUE(TechniqueSet::withS(5).anyUpTo(5));
  EXPECT_FALSE(TechniqueSet::withT(6).anyUpTo(4));
  EXPECT_TRUE(TechniqueSet::withT(6).anyUpTo(5));  // (0,6)
  EXPECT_TRUE(TechniqueSet::withT(2).anyUpTo(1));  // (0,2)
}

TEST(BptTechniqueSet, AHoleInARuleListsTheSetUpToTheMaximum) {
  TechniqueSet set = TechniqueSet::all();
  set.disable({1, 2}, 3);
  EXPECT_FALSE(set.contains(1, 2));
  EXPECT_EQ(set.count(3), 8);
  EXPECT_FALSE(set.contains(0, 5));  // length 4: no longer a rule
  set.enable({1, 2});
  EXPECT_EQ(set, TechniqueSet::all().upTo(3));
  EXPECT_TRUE(set.containsAllUpTo(3));
  EXPECT_FALSE(set.containsAllUpTo(4));
  // A whole rule goes as a whole; what another rule still holds of it, one by one.
  TechniqueSet rules = TechniqueSet::parse("s=2;t=3");
  rules.disable(TechniqueSet::withT(3), 3);
  EXPECT_EQ(rules, TechniqueSet::withS(2));
  rules = TechniqueSet::parse("s=0;s=1;t=2");
  rules.disable(TechniqueSet::withS(1), 4);
  EXPECT_EQ(rules, TechniqueSet::parse("0,2;0,3;0,4;0,5;2,2;3,2"));
}

TEST(BptTechniqueSet, IntersectionsAndLightTracing) {
  EXPECT_EQ(TechniqueSet::all() & TechniqueSet::lightTracing(), TechniqueSet::lightTracing());
  EXPECT_EQ(TechniqueSet::pathTracing() & TechniqueSet::lightTracing(), TechniqueSet::parse("1,1"));
  EXPECT_EQ(TechniqueSet::parse("k=2;s=2;0,4") & TechniqueSet::lightTracing(), TechniqueSet::parse("2,1"));
  EXPECT_EQ(TechniqueSet::parse("s=0;s=3") & TechniqueSet::parse("s=3;t=4"), TechniqueSet::parse("s=3;0,4"));
  RenderSettings s;
  s.integrator = IntegratorKind::Lt;
  s.techniques = TechniqueSet::parse("k=2;1,2;s=3");
  EXPECT_EQ(enabledTechniques(s), TechniqueSet::parse("2,1;3,1"));
  s.integrator = IntegratorKind::Bpt;
  EXPECT_EQ(enabledTechniques(s), s.techniques);
}

TEST(BptTechniqueSet, ListsUncoveredLengths) {
  const TechniqueSet set = TechniqueSet::parse("1,2;k=3");
  EXPECT_EQ(set.uncoveredLengths(4), (std::vector<int>{1, 4}));
}

TEST(BptTechniqueSet, RejectsBadInput) {
  for (const char* bad : {"", "x", "1,", "1;2", "s=", "-1,2", "1,0", "0,1", "all;;", "q=1", "1,2,3", "k=0", "t=0",
                          "s=-1", "k=5000", "4000,4000"})
    EXPECT_THROW(TechniqueSet::parse(bad), std::invalid_argument) << bad;
  try {
    TechniqueSet::parse("1,2;zz");
    ADD_FAILURE() << "accepted zz";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zz"), std::string::npos);
  }
}

}  // namespace
}  // namespace pathlab
