// Technique and TechniqueSet: the one index over connections and merges, the SPEC parser and its canonical printing,
// equality of sets however they are spelled, and a set that does not change with the maximum length.
#include "core/bpt/technique_set.h"
#include "core/render/render_settings.h"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

namespace pathlab {
namespace {

TEST(Technique, OneIndexOverConnectionsAndMergesInTheOrderOfTheGrid) {
  // Length 1: C(0,2), C(1,1); length 2: C(0,3), C(1,2), C(2,1), M(2,2), E(1,2); length 3 from 7.
  EXPECT_EQ((Technique{0, 2}.index()), 0u);
  EXPECT_EQ((Technique{1, 1}.index()), 1u);
  EXPECT_EQ((Technique{0, 3}.index()), 2u);
  EXPECT_EQ((Technique{2, 1}.index()), 4u);
  EXPECT_EQ(Technique::merge(2, 2).index(), 5u);
  EXPECT_EQ(Technique::equiangular(2).index(), 6u);
  EXPECT_EQ((Technique{0, 4}.index()), 7u);
  EXPECT_EQ(Technique::merge(3, 2).index(), 12u);
  EXPECT_EQ(Technique::equiangular(3).index(), 13u);
  EXPECT_EQ(Technique::countUpTo(4), 2u + 5u + 7u + 9u);
  EXPECT_EQ(Technique::countUpTo(4, TechniqueFamilies::Connections), 2u + 3u + 4u + 5u);
  EXPECT_EQ(Technique::countUpTo(4, TechniqueFamilies::Merges), 0u + 1u + 2u + 3u);
  EXPECT_EQ(Technique::countUpTo(4, TechniqueFamilies::Equiangular), 0u + 1u + 1u + 1u);
  EXPECT_EQ(Technique::equiangular(3).length(), 3);  // C(1,3)'s path: 1 + 3 - 1 edges
  EXPECT_FALSE(Technique::equiangular(1).valid());  // its vertex is not the camera
  EXPECT_FALSE((Technique{2, 3, TechniqueKind::Equiangular}.valid()));  // one light vertex only
  EXPECT_EQ((Technique{3, 3}.length()), 5);
  EXPECT_EQ(Technique::merge(3, 3).length(), 4);  // y_2 and z_2 are one vertex: 3 + 3 - 2 edges
  EXPECT_FALSE((Technique{0, 1}.valid()));
  EXPECT_FALSE((Technique{1, 0}.valid()));
  EXPECT_FALSE(Technique::merge(1, 3).valid());  // not on the light
  EXPECT_FALSE(Technique::merge(3, 1).valid());  // not at the camera
  EXPECT_NE(Technique::merge(2, 3), (Technique{2, 3}));
  size_t i = 0, connections = 0, merges = 0, equiangular = 0;
  for (const Technique x : techniquesUpTo(60, TechniqueFamilies::All)) {
    ASSERT_EQ(x.index(), i) << x.s << "," << x.t;
    ASSERT_EQ(Technique::fromIndex(i), x);
    ASSERT_TRUE(x.valid());
    ASSERT_EQ(Technique::atSlot(x.length(), x.slot()), x);
    // Each family keeps a dense numbering of its own (colours are keyed by it).
    ASSERT_EQ(x.familyIndex(), x.isMerge() ? merges++ : x.isEquiangular() ? equiangular++ : connections++);
    ++i;
  }
  EXPECT_EQ(i, Technique::countUpTo(60));
  EXPECT_EQ(connections, Technique::countUpTo(60, TechniqueFamilies::Connections));
  // A family alone skips the other's slots and stops at the same end.
  size_t c = 0;
  for (const Technique x : techniquesUpTo(60)) {
    ASSERT_FALSE(x.isMerge());
    ++c;
  }
  EXPECT_EQ(c, connections);
  size_t m = 0;
  for (const Technique x : techniquesUpTo(60, TechniqueFamilies::Merges)) {
    ASSERT_TRUE(x.isMerge());
    ++m;
  }
  EXPECT_EQ(m, merges);
  size_t e = 0;
  for (const Technique x : techniquesUpTo(60, TechniqueFamilies::Equiangular)) {
    ASSERT_TRUE(x.isEquiangular());
    ++e;
  }
  EXPECT_EQ(e, equiangular);
  EXPECT_EQ(e, Technique::countUpTo(60, TechniqueFamilies::Equiangular));
  std::vector<Technique> row(techniquesOfLength(3).begin(), techniquesOfLength(3).end());
  EXPECT_EQ(row, (std::vector<Technique>{{0, 4}, {1, 3}, {2, 2}, {3, 1}}));
  const TechniqueRange all3 = techniquesOfLength(3, TechniqueFamilies::All);
  std::vector<Technique> rowAll(all3.begin(), all3.end());
  EXPECT_EQ(rowAll, (std::vector<Technique>{{0, 4}, {1, 3}, {2, 2}, {3, 1}, Technique::merge(2, 3), Technique::merge(3, 2),
                                            Technique::equiangular(3)}));
  EXPECT_EQ(techniquesUpTo(0).begin(), techniquesUpTo(0).end());
  const TechniqueRange noMergeOfLength1 = techniquesOfLength(1, TechniqueFamilies::Merges);
  EXPECT_EQ(noMergeOfLength1.begin(), noMergeOfLength1.end());
}

TEST(BptTechniqueSet, MergesAreListedParsedAndPrintedBesideConnections) {
  const TechniqueSet set = TechniqueSet::parse("all; M2,3 ;m=4");
  EXPECT_TRUE(set.contains(Technique::merge(2, 3)));
  EXPECT_FALSE(set.contains(Technique::merge(3, 2)));  // length 3 but not listed
  for (const Technique x : techniquesOfLength(4, TechniqueFamilies::Merges)) EXPECT_TRUE(set.contains(x));
  EXPECT_TRUE(set.contains(2, 3));  // the connection of the same (s, t)
  EXPECT_EQ(set.toString(), "all;M2,3;m=4");
  EXPECT_EQ(TechniqueSet::parse(set.toString()), set);
  EXPECT_EQ(set.families(), TechniqueFamilies::All);
  // "all" is every connection and equiangular technique (bpt samples E where a fog allows).
  EXPECT_EQ(TechniqueSet::all().families(), TechniqueFamilies::Connections | TechniqueFamilies::Equiangular);
  EXPECT_EQ(TechniqueSet::parse("M2,2").families(), TechniqueFamilies::Merges);
  // "all" is every connection and no merge; the counts and the completeness follow.
  EXPECT_FALSE(TechniqueSet::all().contains(Technique::merge(2, 2)));
  EXPECT_EQ(set.count(4), 2 + 3 + 4 + 5 + 1 + 3 + 3);
  EXPECT_TRUE(set.containsAllUpTo(4));
  EXPECT_FALSE(set.containsAllUpTo(4, TechniqueFamilies::All));  // M(2,2) and M(3,2) missing
  EXPECT_FALSE((set | TechniqueSet::parse("M3,2")).containsAllUpTo(4, TechniqueFamilies::All));
  EXPECT_TRUE((set | TechniqueSet::parse("M3,2;M2,2")).containsAllUpTo(4, TechniqueFamilies::All));
  // The set's operations keep merges: disabling one, intersecting, fitting to a maximum.
  TechniqueSet less = set;
  less.disable(Technique::merge(2, 3), 4);
  EXPECT_EQ(less.toString(), "all;m=4");
  EXPECT_EQ((set & TechniqueSet::parse("M2,3;0,2")).toString(), "0,2;M2,3");
  EXPECT_EQ(set.fittedTo(3).toString(), "all;M2,3");
  EXPECT_EQ(TechniqueSet::parse("s=0;M3,3").upTo(4).toString(), "0,2;0,3;0,4;0,5;M3,3");
  try {
    TechniqueSet::parse("s=0;M3,3").checkFits(3);
    ADD_FAILURE() << "M(3,3) has length 4";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("M(3,3) has length 4"), std::string::npos) << e.what();
  }
  // By length, connections first; a length's every merge as m=K (M(2,2) is length 2's only one).
  EXPECT_EQ(TechniqueSet::parse("0,3;M3,2;0,2;M2,2").toString(), "0,2;0,3;m=2;M3,2");
  for (const char* bad : {"M1,3", "M3,1", "m=1", "M2", "Mx,2", "m=0"})
    EXPECT_THROW(TechniqueSet::parse(bad), std::invalid_argument) << bad;
}

TEST(BptTechniqueSet, EveryMergeAtEveryLengthIsOneRule) {
  const TechniqueSet vcm = TechniqueSet::parse("all;m=all");
  EXPECT_EQ(vcm.toString(), "all;m=all");
  EXPECT_EQ(TechniqueSet::parse("m=all;M2,3;m=4"), TechniqueSet::allMerges());  // listed ones absorbed
  for (const Technique x : techniquesUpTo(30, TechniqueFamilies::All)) EXPECT_TRUE(vcm.contains(x));
  EXPECT_FALSE(TechniqueSet::allMerges().contains(1, 1));
  EXPECT_EQ(vcm.families(), TechniqueFamilies::All);
  EXPECT_TRUE(vcm.containsAllUpTo(6, TechniqueFamilies::All));
  EXPECT_EQ(vcm.count(3), 9 + 3 + 2);
  // A hole lists the merges up to the maximum; switching every merge off leaves the connections.
  TechniqueSet less = vcm;
  less.disable(Technique::merge(2, 2), 3);
  EXPECT_EQ(less.toString(), "all;m=3");
  less.disable(TechniqueSet::allMerges(), 3);
  EXPECT_EQ(less, TechniqueSet::all());
  TechniqueSet noC = vcm;
  noC.disable({1, 1}, 2);
  EXPECT_EQ(noC.toString(), "0,2;k=2;m=all");
  EXPECT_EQ((vcm & TechniqueSet::parse("M2,2;s=0")).toString(), "s=0;m=2");
  EXPECT_EQ((TechniqueSet::all() & TechniqueSet::allMerges()), TechniqueSet());
  EXPECT_EQ((vcm & TechniqueSet::allMerges()), TechniqueSet::allMerges());
  EXPECT_TRUE(TechniqueSet::allMerges().anyUpTo(2));
  EXPECT_FALSE(TechniqueSet::allMerges().anyUpTo(1));
}

TEST(BptTechniqueSet, ARendererTakesMergesWhereItCanSampleThem) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.maxLength = 4;
  s.techniques = TechniqueSet::parse("all;M2,2");
  EXPECT_NO_THROW(validateSettings(s));
  auto refused = [&](RenderSettings bad, const std::string& what) {
    try {
      validateSettings(bad);
      ADD_FAILURE() << "accepted: " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  RenderSettings naive = s;
  naive.connect = ConnectStrategy::Endpoints;
  refused(naive, "path reuse");
  RenderSettings check = s;  // the check judges merges by their bias against the radius (merge_bias.h)
  check.checkTechniques = true;
  EXPECT_NO_THROW(validateSettings(check));
  RenderSettings maps = s;  // the technique maps cover merges (tests/maps/technique_maps_merge_test.cpp)
  maps.pyramidLength = 2;
  maps.techniqueMaps = true;
  EXPECT_NO_THROW(validateSettings(maps));
  RenderSettings radius = s;
  radius.mergeRadius = 0.f;
  refused(radius, "--radius");
  RenderSettings alpha = s;
  alpha.mergeRadiusAlpha = 1.5f;
  refused(alpha, "--radius-alpha");
  RenderSettings huge = s;  // 8192 x 8192 pixels, 40 vertices each: the store would take tens of GiB
  huge.width = huge.height = 8192;
  huge.maxLength = 40;
  refused(huge, "GiB of light vertices");
}

TEST(BptTechniqueSet, AllHasEveryTechniqueOfEveryLength) {
  const TechniqueSet set = TechniqueSet::all();
  EXPECT_EQ(set.count(4), 2 + 3 + 4 + 5 + 3);  // and E(1,2), E(1,3), E(1,4)
  EXPECT_TRUE(set.contains(0, 2));
  EXPECT_TRUE(set.contains(4, 1));
  EXPECT_TRUE(set.contains(Technique::equiangular(4)));
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
  EXPECT_EQ(TechniqueSet::parse("s=0;k=2"), TechniqueSet::parse("1,2; s=0 ;2,1;E1,2"));
  EXPECT_NE(TechniqueSet::parse("s=0;k=2"), TechniqueSet::parse("1,2; s=0 ;2,1"));
  // E(1, t) stands beside C(1, t): s = 1 and t = T take it in.
  EXPECT_EQ(TechniqueSet::parse("s=1"), TechniqueSet::parse("s=1;E1,5"));
  EXPECT_EQ(TechniqueSet::parse("t=3"), TechniqueSet::parse("t=3;E1,3"));
  EXPECT_FALSE(TechniqueSet::parse("s=0").contains(Technique::equiangular(3)));
  EXPECT_EQ(TechniqueSet::parse("0,3;E1,2").toString(), "0,3;E1,2");
  EXPECT_EQ(TechniqueSet::parse("all;s=3;1,1"), TechniqueSet::all());
  EXPECT_EQ(TechniqueSet::parse("t=1;1,1;2,1"), TechniqueSet::lightTracing());
  EXPECT_EQ(TechniqueSet::parse("s=1;s=0"), TechniqueSet::parse("s=0;s=1;0,7"));
  // Equal up to length 3 is not equal: they differ once the maximum grows.
  EXPECT_NE(TechniqueSet::pathTracing().upTo(3), TechniqueSet::pathTracing());
  EXPECT_EQ(TechniqueSet::pathTracing().upTo(3).count(3), 6 + 2);  // with E(1,2), E(1,3)
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
  EXPECT_EQ(set.count(3), 8 + 2);
  EXPECT_TRUE(set.contains(Technique::equiangular(2)));  // E(1,2) stays beside the hole at C(1,2)
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
                          "s=-1", "k=5000", "4000,4000", "E2,3", "E1,1", "E0,2"})
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
