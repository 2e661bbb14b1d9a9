// Equiangular sampling (core/media/equiangular.h) against its closed forms: the density integrates
// to one over the segment and is the derivative of the distribution function, the samples follow
// it (Pearson's chi-square with the bin masses from the density, not the distribution function
// the sampler inverts), and its defining property, p(t) |x(t) - c|^2 constant.
#include "core/math/rng.h"
#include "core/media/equiangular.h"
#include "tests/support/chi2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace pathlab {
namespace {

struct Case {
  Vec3 o, d, c;
  float tMax;
};

// A light beside the segment, one behind its start, one past its end, one far to the side, and
// an unbounded segment.
std::vector<Case> cases() {
  return {{Vec3(0.f), Vec3(1.f, 0.f, 0.f), Vec3(2.f, 0.3f, 0.f), 5.f},
          {Vec3(1.f, 2.f, 3.f), glm::normalize(Vec3(1.f, 1.f, 0.f)), Vec3(0.f, 1.f, 3.5f), 4.f},
          {Vec3(0.f), Vec3(0.f, 0.f, 1.f), Vec3(0.1f, 0.f, 9.f), 3.f},
          {Vec3(0.f), Vec3(0.f, 1.f, 0.f), Vec3(20.f, 1.f, 0.f), 2.f},
          {Vec3(0.f), Vec3(1.f, 0.f, 0.f), Vec3(1.f, 0.5f, 0.f), std::numeric_limits<float>::infinity()}};
}

// Simpson's rule of the density over [a, b] in n panels.
double integrate(const EquiangularSegment& s, double a, double b, int n) {
  const double h = (b - a) / n;
  double sum = equiangularPdf(s, float(a)) + equiangularPdf(s, float(b));
  for (int i = 1; i < n; ++i) sum += (i % 2 ? 4.0 : 2.0) * equiangularPdf(s, float(a + i * h));
  return sum * h / 3.0;
}

TEST(Equiangular, DensityIsNormalisedAndFollowsTheInverseSquare) {
  for (const Case& k : cases()) {
    const auto s = equiangularSegment(k.o, k.d, k.tMax, k.c);
    ASSERT_TRUE(s);
    const double end = std::isfinite(k.tMax) ? k.tMax : 1e5;
    // An unbounded segment's tail past 1e5 holds D / ((thetaB - thetaA) t) of the mass.
    const double tail = std::isfinite(k.tMax) ? 0.0 : s->D / (s->phiMax * end);
    EXPECT_NEAR(integrate(*s, 0.0, std::min(end, 50.0), 20000) + (end > 50.0 ? integrate(*s, 50.0, end, 200000) : 0.0) +
                    tail,
                1.0, 2e-4);
    // p(t) |x(t) - c|^2 is the same at every t, (thetaB - thetaA)^-1 D.
    for (float t : {0.f, 0.3f, 1.f, 1.9f}) {
      const Vec3 x = k.o + t * k.d;
      const float r2 = glm::dot(x - k.c, x - k.c);
      EXPECT_NEAR(equiangularPdf(*s, t) * r2, s->D / s->phiMax, 1e-4 * s->D / s->phiMax);
    }
    // Zero outside the segment.
    EXPECT_EQ(equiangularPdf(*s, -0.01f), 0.f);
    if (std::isfinite(k.tMax)) {
      EXPECT_EQ(equiangularPdf(*s, k.tMax * 1.01f), 0.f);
    }
    // The density is the distribution function's derivative.
    for (float t : {0.2f, 1.1f, 1.8f}) {
      const float h = 1e-3f;
      EXPECT_NEAR((equiangularCdf(*s, t + h) - equiangularCdf(*s, t - h)) / (2.f * h), equiangularPdf(*s, t),
                  2e-3f * equiangularPdf(*s, t));
    }
  }
}

TEST(Equiangular, SamplesFollowTheDensity) {
  Pcg32 rng(17, 5);
  for (const Case& k : cases()) {
    const auto s = equiangularSegment(k.o, k.d, k.tMax, k.c);
    ASSERT_TRUE(s);
    // Bins over [0, end) and one for the rest (the unbounded segment's tail).
    const float end = std::isfinite(k.tMax) ? k.tMax : 10.f;
    const int bins = 40, n = 200000;
    std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
    for (int i = 0; i < n; ++i) {
      const float t = sampleEquiangular(*s, rng.next1D());
      ASSERT_TRUE(t >= 0.f && t <= k.tMax) << t;
      observed[t < end ? std::min(static_cast<int>(t / end * bins), bins - 1) : bins] += 1.0;
    }
    double inside = 0.0;
    for (int b = 0; b < bins; ++b) {
      expected[b] = n * integrate(*s, double(end) * b / bins, double(end) * (b + 1) / bins, 200);
      inside += expected[b];
    }
    expected[bins] = n - inside;
    double chi2 = 0.0;
    int cells = 0;
    for (int b = 0; b <= bins; ++b) {
      if (expected[b] < 5.0) {
        EXPECT_LT(observed[b], 20.0) << "bin " << b;
        continue;
      }
      chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
      ++cells;
    }
    const double p = test::regularizedGammaQ((cells - 1) / 2.0, chi2 / 2.0);
    EXPECT_GT(p, 0.002) << "chi2 " << chi2 << " over " << cells << " cells, light at " << k.c.x << "," << k.c.y << ","
                        << k.c.z;
  }
}

// A light on the ray's line: the density would be a spike, and the segment declines it.
TEST(Equiangular, LightOnTheLineIsDeclined) {
  EXPECT_FALSE(equiangularSegment(Vec3(0.f), Vec3(1.f, 0.f, 0.f), 5.f, Vec3(2.f, 0.f, 0.f)));
  EXPECT_FALSE(equiangularSegment(Vec3(0.f), Vec3(1.f, 0.f, 0.f), 0.f, Vec3(2.f, 1.f, 0.f)));
  EXPECT_TRUE(equiangularSegment(Vec3(0.f), Vec3(1.f, 0.f, 0.f), 5.f, Vec3(2.f, 1e-3f, 0.f)));
}

}  // namespace
}  // namespace pathlab
