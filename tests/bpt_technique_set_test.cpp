// TechniqueSet: the (s, t) mask, its SPEC parser and the lengths left uncovered.
#include "core/bpt/technique_set.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace pathlab {
namespace {

TEST(BptTechniqueSet, AllHasEveryTechniqueUpToMaxLength) {
  const TechniqueSet set = TechniqueSet::all(4);
  EXPECT_EQ(set.size(), 2 + 3 + 4 + 5);
  EXPECT_TRUE(set.contains(0, 2));
  EXPECT_TRUE(set.contains(4, 1));
  EXPECT_FALSE(set.contains(5, 1));  // length 5
  EXPECT_FALSE(set.contains(1, 0));  // t >= 1
  EXPECT_FALSE(set.contains(0, 1));  // length 0
  EXPECT_TRUE(set.uncoveredLengths().empty());
}

TEST(BptTechniqueSet, ParsesEveryItemKind) {
  const TechniqueSet set = TechniqueSet::parse(" 1,2 ; s=0;t=1; k=4", 5);
  EXPECT_TRUE(set.contains(1, 2));
  for (int t = 2; t <= 6; ++t) EXPECT_TRUE(set.contains(0, t));
  for (int s = 1; s <= 5; ++s) EXPECT_TRUE(set.contains(s, 1));
  for (int s = 0; s <= 4; ++s) EXPECT_TRUE(set.contains(s, 5 - s));
  EXPECT_FALSE(set.contains(2, 2));
  EXPECT_EQ(TechniqueSet::parse("all", 3), TechniqueSet::all(3));
  TechniqueSet manual(3);
  manual.enable(2, 2);
  manual.disable(2, 2);
  EXPECT_EQ(manual.size(), 0);
}

TEST(BptTechniqueSet, ListsUncoveredLengths) {
  const TechniqueSet set = TechniqueSet::parse("1,2;k=3", 4);
  EXPECT_EQ(set.uncoveredLengths(), (std::vector<int>{1, 4}));
}

TEST(BptTechniqueSet, RejectsBadInput) {
  for (const char* bad : {"", "x", "1,", "1;2", "s=", "k=9", "3,3", "-1,2", "1,0", "all;;", "q=1", "1,2,3"})
    EXPECT_THROW(TechniqueSet::parse(bad, 4), std::invalid_argument) << bad;
  try {
    TechniqueSet::parse("1,2;zz", 4);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zz"), std::string::npos);
  }
}

}  // namespace
}  // namespace pathlab
