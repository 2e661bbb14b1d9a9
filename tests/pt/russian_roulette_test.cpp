// The Russian roulette policy shared by the path tracer and the bidirectional walks
// (core/sampling/russian_roulette.h): a delta bounce never lowers the continuation probability,
// survivors are reweighted so the expected throughput is unchanged, and it stays bounded.
#include "core/sampling/russian_roulette.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

constexpr int kLate = kRussianRouletteStart + 2;  // an edge count where roulette applies

// Entering glass from air in radiance mode scales the throughput by 1 / eta^2 (0.39 at eta 1.6)
// and a coloured mirror by its reflectance: neither is a reason to end the path.
TEST(RussianRoulette, DeltaBounceDoesNotLowerContinuation) {
  const Spectrum before(0.8f, 0.6f, 0.4f);
  for (const float factor : {1.f / (1.6f * 1.6f), 0.05f, 0.5f, 1.f, 2.56f}) {
    EXPECT_EQ(RussianRoulette::continuation(before, before * factor, true), 1.f) << factor;
    RussianRoulette roulette(Spectrum(1.f));
    Pcg32 rng(7, 3);
    for (int i = 0; i < 1000; ++i) {
      Spectrum beta = before * factor;
      ASSERT_TRUE(roulette.survives(beta, true, kLate, rng)) << factor;
      EXPECT_EQ(beta, before * factor);
    }
  }
}

// A diffuse bounce of albedo rho continues with probability rho, whatever came before (a glass
// sphere's 1 / eta^2 earlier on the path included).
TEST(RussianRoulette, DiffuseBounceContinuesWithItsAlbedo) {
  const Spectrum before = Spectrum(1.f / (1.6f * 1.6f));
  const Spectrum albedo(0.73f, 0.5f, 0.2f);
  EXPECT_FLOAT_EQ(RussianRoulette::continuation(before, before * albedo, false), 0.73f);
  EXPECT_EQ(RussianRoulette::continuation(before, before * 1.5f, false), 1.f);
}

// Unbiased: the mean of the reweighted throughput over many decisions is the throughput; bounded:
// a survivor's throughput is at most the one before the bounce.
TEST(RussianRoulette, SurvivorsKeepTheExpectedThroughputAndStayBounded) {
  const Spectrum before(0.5f, 0.25f, 0.125f), after = before * Spectrum(0.3f, 0.2f, 0.1f);
  Pcg32 rng(11, 5);
  const int n = 200000;
  double sum = 0.0;
  int survivors = 0;
  for (int i = 0; i < n; ++i) {
    RussianRoulette roulette(Spectrum(1.f));
    Spectrum beta = before;
    ASSERT_TRUE(roulette.survives(beta, false, kRussianRouletteStart - 1, rng));  // before the start: kept
    beta = after;
    if (!roulette.survives(beta, false, kLate, rng)) continue;
    ++survivors;
    sum += beta.r;
    EXPECT_LE(maxComponent(beta), maxComponent(before) * (1.f + 1e-6f));
  }
  // q = 0.3; the mean of the survivors' weight times their fraction is after.r, standard error
  // after.r sqrt((1 - q) / (q n)) = 0.00016.
  EXPECT_NEAR(double(survivors) / n, 0.3, 5 * std::sqrt(0.3 * 0.7 / n));
  EXPECT_NEAR(sum / n, after.r, 5 * after.r * std::sqrt(0.7 / (0.3 * n)));
}

// Paths shorter than kRussianRouletteStart edges always continue.
TEST(RussianRoulette, NoDecisionBeforeTheStart) {
  RussianRoulette roulette(Spectrum(1.f));
  Pcg32 rng(3, 1);
  Spectrum beta(1.f);
  for (int edges = 1; edges < kRussianRouletteStart; ++edges) {
    beta *= 0.01f;
    const Spectrum kept = beta;
    ASSERT_TRUE(roulette.survives(beta, false, edges, rng));
    EXPECT_EQ(beta, kept);
  }
}

}  // namespace
}  // namespace pathlab
