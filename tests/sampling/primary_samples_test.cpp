// The primary sample vector's mutations (core/sampling/primary_samples.h): a rejected proposal
// leaves the state as it was, a small step moves a coordinate by a wrapped normal of deviation
// sigma, a coordinate left unread for n small steps catches up by one of deviation sigma sqrt(n),
// a large step draws every coordinate afresh, and the streams interleave.
#include "core/sampling/primary_samples.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pathlab {
namespace {

// The signed distance from a to b on the unit circle, in [-0.5, 0.5).
double circleDistance(double a, double b) {
  double d = b - a;
  d -= std::floor(d + 0.5);
  return d;
}

TEST(PrimarySamples, ARejectedProposalRestoresEveryCoordinate) {
  PrimarySamples x(Pcg32(1, 2), 0.05f, 0.3f);
  for (size_t i = 0; i < 8; ++i) x.get(i);
  for (int iteration = 0; iteration < 200; ++iteration) {
    std::vector<float> before;
    for (size_t i = 0; i < 8; ++i) before.push_back(x.get(i));
    x.startIteration();
    // The proposal reads some coordinates, and new ones past the end.
    for (size_t i = 0; i < 12; i += 1 + iteration % 3) x.get(i);
    if (iteration % 2 == 0) {
      x.reject();
      for (size_t i = 0; i < 8; ++i) EXPECT_EQ(x.get(i), before[i]) << "iteration " << iteration << " coordinate " << i;
    } else {
      x.accept();
    }
  }
}

TEST(PrimarySamples, EveryValueIsInTheUnitInterval) {
  PrimarySamples x(Pcg32(3, 4), 0.3f, 0.1f);
  for (int iteration = 0; iteration < 20000; ++iteration) {
    x.startIteration();
    for (size_t i = 0; i < 4; ++i) {
      const float u = x.get(i);
      ASSERT_TRUE(u >= 0.f && u < 1.f) << u;
    }
    x.accept();
  }
}

// Small steps only, every one accepted: coordinate 0, read every iteration, moves by N(0, sigma^2);
// coordinate 1, read every 16th, by N(0, 16 sigma^2) between its reads.
TEST(PrimarySamples, SmallStepsSpreadBySigmaAndCatchUpOverMissedSteps) {
  const float sigma = 0.01f;
  PrimarySamples x(Pcg32(5, 6), sigma, 0.f);
  test::RunningStats every, sparse, everyMean;
  double last0 = x.get(0), last1 = x.get(1);
  for (int iteration = 1; iteration <= 64000; ++iteration) {
    x.startIteration();
    const double u0 = x.get(0);
    const double d0 = circleDistance(last0, u0);
    every.add(d0 * d0);
    everyMean.add(d0);
    last0 = u0;
    if (iteration % 16 == 0) {
      const double u1 = x.get(1);
      const double d1 = circleDistance(last1, u1);
      sparse.add(d1 * d1);
      last1 = u1;
    }
    x.accept();
  }
  const double s2 = static_cast<double>(sigma) * sigma;
  EXPECT_LT(std::abs(every.estimate().zScore(s2)), test::kMaxZ) << every.mean() / s2;
  EXPECT_LT(std::abs(everyMean.estimate().zScore(0.0)), test::kMaxZ);
  EXPECT_LT(std::abs(sparse.estimate().zScore(16 * s2)), test::kMaxZ) << sparse.mean() / s2;
}

// Large steps only: consecutive values are independent uniforms (mean 1/2, variance 1/12,
// uncorrelated), whether or not the coordinate was read at each step.
TEST(PrimarySamples, LargeStepsDrawEveryCoordinateAfresh) {
  PrimarySamples x(Pcg32(7, 8), 0.01f, 1.f);
  test::RunningStats mean, variance, product;
  double last = x.get(0);
  for (int iteration = 1; iteration <= 40000; ++iteration) {
    x.startIteration();
    if (iteration % 2 == 0) {  // coordinate 0 skips every other large step
      const double u = x.get(0);
      mean.add(u);
      variance.add((u - 0.5) * (u - 0.5));
      product.add((u - 0.5) * (last - 0.5));
      last = u;
    }
    x.get(1);
    x.accept();
  }
  EXPECT_LT(std::abs(mean.estimate().zScore(0.5)), test::kMaxZ);
  EXPECT_LT(std::abs(variance.estimate().zScore(1.0 / 12.0)), test::kMaxZ);
  EXPECT_LT(std::abs(product.estimate().zScore(0.0)), test::kMaxZ);
}

// A rejected large step leaves a coordinate it did not read where it was: the next small step
// moves it by sigma, not to a fresh value.
TEST(PrimarySamples, ARejectedLargeStepDoesNotRefreshUnreadCoordinates) {
  PrimarySamples x(Pcg32(9, 10), 0.001f, 0.5f);
  x.get(0), x.get(1);
  int checked = 0;
  for (int iteration = 0; iteration < 2000; ++iteration) {
    const float before = x.get(1);
    x.startIteration();
    const bool large = x.largeStep();
    x.get(0);
    x.reject();
    x.startIteration();
    const float after = x.get(1);
    if (large && !x.largeStep()) {
      EXPECT_LT(std::abs(circleDistance(before, after)), 0.01) << "iteration " << iteration;
      ++checked;
    }
    x.accept();
  }
  EXPECT_GT(checked, 100);
}

// The streams interleave: stream j's i-th number is coordinate i * kStreams + j, so one stream
// reading more does not shift another's.
TEST(PrimarySamples, StreamsReadInterleavedCoordinates) {
  PrimarySamples x(Pcg32(11, 12), 0.01f, 0.3f);
  PrimarySampleStream light(x, 1);
  const float l0 = light.next1D(), l1 = light.next1D();
  PrimarySampleStream camera(x, 0);
  for (int i = 0; i < 5; ++i) camera.next1D();
  EXPECT_EQ(x.get(1), l0);
  EXPECT_EQ(x.get(1 + PrimarySamples::kStreams), l1);
  EXPECT_EQ(x.size(), 4u * PrimarySamples::kStreams + 1);
}

}  // namespace
}  // namespace pathlab
