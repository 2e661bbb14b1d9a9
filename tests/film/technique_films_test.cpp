// TechniqueFilms over the one technique index: a family not asked for costs nothing and ignores
// what is added to it; a merge's films sit beside the connections' without touching them; the
// second moments across passes give each pass's estimate's variance, splats scaled as the film
// scales a pass's.
#include "core/film/technique_films.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

TEST(TechniqueFilms, AFamilyNotAskedForCostsNoMemory) {
  const uint64_t connections = TechniqueFilms::bytesFor(64, 32, 6, true);
  const uint64_t both = TechniqueFilms::bytesFor(64, 32, 6, true, TechniqueFamilies::Connections | TechniqueFamilies::Merges);
  const uint64_t every = TechniqueFilms::bytesFor(64, 32, 6, true, TechniqueFamilies::All);
  // 27 connections, 15 merges and 5 equiangular techniques up to length 6, 8 doubles a pixel each.
  EXPECT_EQ(connections, 27u * 8u * 8u * 64u * 32u);
  EXPECT_EQ(both, (27u + 15u) * 8u * 8u * 64u * 32u);
  EXPECT_EQ(every, (27u + 15u + 5u) * 8u * 8u * 64u * 32u);
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

// Two passes by hand: (0,2) gives a pixel 1 then 3 (variance 2); (2,1) splats 0.5 and 1.5 there
// in the first pass and nothing in the second, each pass's splats scaled by 16 pixels / 32 light
// subpaths, so its pass estimates are 1 and 0 (variance 0.5); a discarded pass adds nothing.
TEST(TechniqueFilms, SecondMomentsGiveThePassEstimatesVariance) {
  TechniqueFilms films(4, 4, 2, false, TechniqueFamilies::Connections, true);
  ASSERT_TRUE(films.keepsMoments());
  EXPECT_EQ(TechniqueFilms::bytesFor(4, 4, 2, false, TechniqueFamilies::Connections, true),
            TechniqueFilms::bytesFor(4, 4, 2) + 5u * 2u * 8u * 16u);
  const Technique camera{0, 2}, splat{2, 1};
  const Vec2 at(1.5f, 1.5f);
  films.add(camera, at, Spectrum(1.f), Spectrum(1.f));  // grey: luminance 1
  films.add(splat, at, Spectrum(0.5f), Spectrum(1.f));
  films.add(splat, at, Spectrum(1.5f), Spectrum(1.f));
  films.finishPass(16.0 / 32.0);
  films.add(camera, at, Spectrum(9.f), Spectrum(1.f));
  films.discardPass();  // a cancelled pass
  films.add(camera, at, Spectrum(3.f), Spectrum(1.f));
  films.finishPass(16.0 / 32.0);
  // Two passes: 2 samples a pixel, 64 light subpaths; (the discarded 9 is in the weighted film,
  // which a cancelled session is thrown away with; taken out here.)
  films.add(camera, at, Spectrum(-9.f), Spectrum(-1.f));
  films.discardPass();
  const size_t pixel = 1 * 4 + 1;
  EXPECT_NEAR(films.readout(camera, false, 2, 64).at(1, 1).x, 2.f, 1e-6f);
  EXPECT_NEAR(films.readoutVariance(camera, 2, 2, 64)[pixel], 2.f, 1e-5f);
  EXPECT_NEAR(films.readout(splat, false, 2, 64).at(1, 1).x, 0.5f, 1e-6f);
  EXPECT_NEAR(films.readoutVariance(splat, 2, 2, 64)[pixel], 0.5f, 1e-5f);
  EXPECT_EQ(films.readoutVariance(camera, 2, 2, 64)[0], 0.f);  // nothing there
  EXPECT_EQ(films.readoutVariance(camera, 1, 1, 32)[pixel], 0.f);  // one pass: no variance
  // The moments travel with the sums (an MPI job adds them).
  size_t values = 0;
  for (const std::span<double> b : films.sums()) values += b.size();
  EXPECT_EQ(values, 5u * 2u * 3u * 16u + 5u * 16u);
}

}  // namespace
}  // namespace pathlab
