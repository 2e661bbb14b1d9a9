// The per-technique counter table shared by `pathlab render --stats` and the viewer: shares of rays
// and time, the time per try over the timed samples only, sorting, cells and the text table.
#include "core/metrics/technique_table.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace pathlab {
namespace {

Counters sampleCounters() {
  Counters c;
  c.cameraSamples = 100;
  c.timedSamples = 50;
  c.rays = 300;
  c.cameraWalk = {200, 4000};
  c.lightWalk = {100, 2000};
  TechniqueCounters& nee = c.technique(1, 2);
  nee.tried = 100;
  nee.shadowRays = 80;
  nee.blocked = 30;
  nee.contributed = 50;
  nee.nanoseconds = 3000;
  TechniqueCounters& lt = c.technique(2, 1);
  lt.tried = 40;
  lt.shadowRays = 20;
  lt.blocked = 5;
  lt.contributed = 15;
  lt.nanoseconds = 1000;
  c.shadowRays = 100;
  return c;
}

TEST(TechniqueTable, SharesOfRaysAndTime) {
  std::vector<TechniqueRow> rows = techniqueRows(sampleCounters(), 3, 2.0);
  ASSERT_EQ(rows.size(), 4u);  // two walks and the two techniques tried
  EXPECT_EQ(rows[0].name, "camera walks");
  EXPECT_EQ(rows[1].name, "light walks");
  EXPECT_EQ(rows[2].name, "(1,2)");
  EXPECT_EQ(rows[3].name, "(2,1)");
  const double allRays = 400.0, allTime = 10000.0;
  EXPECT_DOUBLE_EQ(rows[0].rayShare, 200.0 / allRays);
  EXPECT_DOUBLE_EQ(rows[2].rayShare, 80.0 / allRays);
  EXPECT_DOUBLE_EQ(rows[2].timeShare, 3000.0 / allTime);
  EXPECT_DOUBLE_EQ(rows[3].raysPerSecond, 10.0);
  // Half the samples were timed: 3000 ns over 50 timed tries.
  EXPECT_DOUBLE_EQ(rows[2].nanosecondsPerTry, 60.0);
  double rayShares = 0.0, timeShares = 0.0;
  for (const TechniqueRow& r : rows) rayShares += r.rayShare, timeShares += r.timeShare;
  EXPECT_NEAR(rayShares, 1.0, 1e-12);
  EXPECT_NEAR(timeShares, 1.0, 1e-12);

  sortRows(rows, TechniqueColumn::TimeShare, true);
  EXPECT_EQ(rows[0].name, "camera walks");
  EXPECT_EQ(rows[1].name, "(1,2)");
  sortRows(rows, TechniqueColumn::Rays, false);
  EXPECT_EQ(rows[0].name, "(2,1)");
  sortRows(rows, TechniqueColumn::Name, false);
  EXPECT_EQ(rows[0].name, "camera walks");
  EXPECT_EQ(rows[3].name, "(2,1)");
}

// With merges, the merge pass and the searches are rows beside the walks, per camera sample, and
// their time counts in the shares.
TEST(TechniqueTable, MergePassAndSearchesAreRows) {
  Counters c = sampleCounters();
  c.mergePass = {100, 6000};
  c.mergeSearch = {0, 4000};
  c.rays += 100;
  const std::vector<TechniqueRow> rows = techniqueRows(c, 3, 2.0);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows[2].name, "merge pass");
  EXPECT_EQ(rows[3].name, "merge searches");
  EXPECT_TRUE(rows[2].walk);
  EXPECT_EQ(rows[2].tried, 100u);
  EXPECT_DOUBLE_EQ(rows[2].timeShare, 6000.0 / 20000.0);
  EXPECT_DOUBLE_EQ(rows[3].timeShare, 4000.0 / 20000.0);
  EXPECT_DOUBLE_EQ(rows[2].rayShare, 100.0 / 500.0);
  // 50 timed samples: 80 ns of search per sample.
  EXPECT_DOUBLE_EQ(rows[3].nanosecondsPerTry, 80.0);
}

TEST(TechniqueTable, NoTimingNoShares) {
  Counters c = sampleCounters();
  c.timedSamples = 0;
  c.cameraWalk.nanoseconds = c.lightWalk.nanoseconds = 0;
  for (TechniqueCounters& t : c.techniques) t.nanoseconds = 0;
  for (const TechniqueRow& r : techniqueRows(c, 3, 1.0)) {
    EXPECT_EQ(r.timeShare, 0.0) << r.name;
    EXPECT_EQ(r.nanosecondsPerTry, 0.0) << r.name;
  }
}

TEST(TechniqueTable, CellsAndTextShowTheSameColumns) {
  const std::vector<TechniqueRow> rows = techniqueRows(sampleCounters(), 3, 2.0);
  EXPECT_EQ(techniqueCell(rows[2], TechniqueColumn::Name, true), "(1,2)");
  EXPECT_EQ(techniqueCell(rows[2], TechniqueColumn::BlockedShare, true), "30%");
  EXPECT_EQ(techniqueCell(rows[2], TechniqueColumn::RayShare, true), "20.0");
  EXPECT_EQ(techniqueCell(rows[2], TechniqueColumn::TimePerTry, true), "60");
  EXPECT_EQ(techniqueCell(rows[2], TechniqueColumn::TimePerTry, false), "-");  // nothing timed
  EXPECT_EQ(techniqueCell(rows[0], TechniqueColumn::Blocked, true), "");         // a walk has no connections
  Counters many;
  many.technique(0, 2).tried = 12'345'678;
  EXPECT_EQ(techniqueCell(techniqueRows(many, 1, 1.0)[0], TechniqueColumn::Tried, false), "12.35M");
  const std::string text = techniqueTableText(rows, true);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 5);  // a header and four rows
  for (const TechniqueColumnInfo& c : techniqueColumns()) EXPECT_NE(text.find(c.header), std::string::npos) << c.header;
  EXPECT_NE(text.find("light walks"), std::string::npos);
}

}  // namespace
}  // namespace pathlab
