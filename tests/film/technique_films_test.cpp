// TechniqueFilms over the one technique index: a family not asked for costs nothing and ignores
// what is added to it; a merge's films sit beside the connections' without touching them.
#include "core/film/technique_films.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

TEST(TechniqueFilms, AFamilyNotAskedForCostsNoMemory) {
  const uint64_t connections = TechniqueFilms::bytesFor(64, 32, 6, true);
  const uint64_t both = TechniqueFilms::bytesFor(64, 32, 6, true, TechniqueFamilies::All);
  // 27 connections and 15 merges up to length 6, 8 doubles a pixel each.
  EXPECT_EQ(connections, 27u * 8u * 8u * 64u * 32u);
  EXPECT_EQ(both, (27u + 15u) * 8u * 8u * 64u * 32u);
  TechniqueFilms films(4, 4, 3);
  const Technique m = Technique::merge(2, 2);
  EXPECT_FALSE(films.covers(m));
  films.add(m, Vec2(1.5f), Spectrum(1.f), Spectrum(2.f));  // ignored
  EXPECT_EQ(films.readout(m, false, 1, 1).at(1, 1), Vec3(0.f));
  size_t allocated = 0;
  for (const std::span<double> b : films.sums()) allocated += b.size();
  EXPECT_EQ(allocated, Technique::countUpTo(3, TechniqueFamilies::Connections) * 2u * 3u * 16u);
}

TEST(TechniqueFilms, AMergeAccumulatesBesideTheConnectionsOfItsLength) {
  TechniqueFilms films(4, 4, 3, true, TechniqueFamilies::All);
  const Technique m = Technique::merge(2, 3), c{2, 2};  // both of length 3
  ASSERT_TRUE(films.covers(m));
  films.add(m, Vec2(2.5f, 1.5f), Spectrum(0.25f), Spectrum(1.f));
  films.add(c, Vec2(2.5f, 1.5f), Spectrum(0.75f), Spectrum(1.f));
  // Two samples per pixel: a merge lands on the sample's own pixel like a camera-side connection.
  EXPECT_FLOAT_EQ(films.readout(m, false, 2, 16).at(2, 1).x, 0.125f);
  EXPECT_FLOAT_EQ(films.readout(m, true, 2, 16).at(2, 1).x, 0.5f);
  EXPECT_FLOAT_EQ(films.readout(c, false, 2, 16).at(2, 1).x, 0.375f);
  EXPECT_FLOAT_EQ(films.readout(Technique::merge(3, 2), false, 2, 16).at(2, 1).x, 0.f);
  // The sampleable films by slot: bit m.slot() credits the merge, bit 2 the connection (2, 2).
  films.addSampleable(3, uint64_t{1} << m.slot() | uint64_t{1} << c.slot(), Vec2(2.5f, 1.5f), false, 4.0);
  EXPECT_FLOAT_EQ(films.readoutSampleable(m, 2, 16)[1 * 4 + 2], 2.f);
  EXPECT_FLOAT_EQ(films.readoutSampleable(c, 2, 16)[1 * 4 + 2], 2.f);
  EXPECT_FLOAT_EQ(films.readoutSampleable(Technique{1, 3}, 2, 16)[1 * 4 + 2], 0.f);
}

}  // namespace
}  // namespace pathlab
