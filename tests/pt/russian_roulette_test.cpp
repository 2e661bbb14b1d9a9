// The Russian roulette policy shared by the path tracer and the bidirectional walks
// (core/sampling/russian_roulette.h): a delta bounce never lowers the continuation probability,
// survivors are reweighted so the expected throughput is unchanged, and it stays bounded.
#include "core/sampling/russian_roulette.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

// A roulette past its start: kRussianRouletteStart non-delta scatterings that kept the throughput.
RussianRoulette started(RouletteCount count, Pcg32& rng) {
  RussianRoulette roulette(Spectrum(1.f), count);
  for (int i = 0; i < kRussianRouletteStart; ++i) {
    Spectrum beta(1.f);
    EXPECT_TRUE(roulette.survives(beta, false, rng));
  }
  return roulette;
}

// Entering glass from air in radiance mode scales the throughput by 1 / eta^2 (0.39 at eta 1.6)
// and a coloured mirror by its reflectance: neither is a reason to end the path.
TEST(RussianRoulette, DeltaBounceDoesNotLowerContinuation) {
  const Spectrum before(0.8f, 0.6f, 0.4f);
  for (const float factor : {1.f / (1.6f * 1.6f), 0.05f, 0.5f, 1.f, 2.56f}) {
    EXPECT_EQ(RussianRoulette::continuation(before, before * factor, true), 1.f) << factor;
    Pcg32 rng(7, 3);
    RussianRoulette roulette = started(RouletteCount::Scatterings, rng);
    for (int i = 0; i < 1000; ++i) {
      Spectrum beta = before * factor;
      ASSERT_TRUE(roulette.survives(beta, true, rng)) << factor;
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
    RussianRoulette roulette(Spectrum(1.f), RouletteCount::Scatterings);
    Spectrum beta = before;
    ASSERT_TRUE(roulette.survives(beta, false, rng));  // the first scattering: before the start, kept
    beta = after;
    if (!roulette.survives(beta, false, rng)) continue;
    ++survivors;
    sum += beta.r;
    EXPECT_LE(maxComponent(beta), maxComponent(before) * (1.f + 1e-6f));
  }
  // q = 0.3; the mean of the survivors' weight times their fraction is after.r, standard error
  // after.r sqrt((1 - q) / (q n)) = 0.00016.
  EXPECT_NEAR(double(survivors) / n, 0.3, 5 * std::sqrt(0.3 * 0.7 / n));
  EXPECT_NEAR(sum / n, after.r, 5 * after.r * std::sqrt(0.7 / (0.3 * n)));
}

// Before kRussianRouletteStart scatterings a walk always continues, whatever it lost.
TEST(RussianRoulette, NoDecisionBeforeTheStart) {
  for (const RouletteCount count : {RouletteCount::Scatterings, RouletteCount::NonDeltaScatterings}) {
    RussianRoulette roulette(Spectrum(1.f), count);
    Pcg32 rng(3, 1);
    Spectrum beta(1.f);
    for (int scatterings = 1; scatterings < kRussianRouletteStart; ++scatterings) {
      beta *= 0.01f;
      const Spectrum kept = beta;
      ASSERT_TRUE(roulette.survives(beta, false, rng));
      EXPECT_EQ(beta, kept);
    }
  }
}

// A camera walk's delta bounces do not count toward the start: the wall a mirror shows gets its
// next bounce as surely as a wall seen directly. A light walk's do: after light -> glass, the first
// diffuse scattering is a decision. Every survivor here has beta 0.01 (q = 0.01), so a decision
// shows as a walk that ended, 99 % of the time.
TEST(RussianRoulette, CameraWalkDeltaBouncesDoNotAdvanceTheStart) {
  auto survivors = [](RouletteCount count, int deltaBounces) {
    int n = 0;
    Pcg32 rng(5, 9);
    for (int i = 0; i < 1000; ++i) {
      RussianRoulette roulette(Spectrum(1.f), count);
      Spectrum beta(1.f);
      for (int d = 0; d < deltaBounces; ++d) EXPECT_TRUE(roulette.survives(beta, true, rng));
      beta *= 0.01f;  // the first non-delta scattering, albedo 0.01
      n += roulette.survives(beta, false, rng) ? 1 : 0;
    }
    return n;
  };
  for (const int deltas : {1, 2, 5}) {
    EXPECT_EQ(survivors(RouletteCount::NonDeltaScatterings, deltas), 1000) << deltas;
    EXPECT_LT(survivors(RouletteCount::Scatterings, deltas), 50) << deltas;  // about 10
  }
  EXPECT_EQ(survivors(RouletteCount::Scatterings, 0), 1000);  // the first scattering of either
}

}  // namespace
}  // namespace pathlab
