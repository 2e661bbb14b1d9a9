// Error metrics against hand-computed values, and the two-buffer estimate against both hand
// computation and the known variance of synthetic passes.
#include "core/metrics/error_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace pathlab {
namespace {

Image onePixel(float r, float g, float b) { return Image{1, 1, {r, g, b}}; }

TEST(ErrorMetrics, HandComputedValues) {
  // Differences (0, 1, -0.5) against a reference (1, 1, 0.5), ε = 0.01.
  const ErrorMetrics m = errorMetrics(onePixel(1.f, 2.f, 0.f), onePixel(1.f, 1.f, 0.5f));
  EXPECT_DOUBLE_EQ(m.mse, (0.0 + 1.0 + 0.25) / 3.0);
  EXPECT_DOUBLE_EQ(m.rmse, std::sqrt(1.25 / 3.0));
  EXPECT_NEAR(m.relMse, (0.0 / 1.01 + 1.0 / 1.01 + 0.25 / 0.26) / 3.0, 1e-12);
  EXPECT_NEAR(m.mape, (0.0 / 1.01 + 1.0 / 1.01 + 0.5 / 0.51) / 3.0, 1e-12);
}

TEST(ErrorMetrics, IdenticalImagesHaveNoError) {
  const Image a{2, 1, {0.f, 1.f, 2.f, 3.f, 4.f, 5.f}};
  const ErrorMetrics m = errorMetrics(a, a);
  EXPECT_EQ(m.mse, 0.0);
  EXPECT_EQ(m.relMse, 0.0);
  EXPECT_EQ(m.mape, 0.0);
}

TEST(ErrorMetrics, BlackReferencePixelsUseEpsilon) {
  // x = 0.1 against r = 0: relMSE = 0.01 / 0.01 = 1, MAPE = 0.1 / 0.01 = 10.
  const ErrorMetrics m = errorMetrics(onePixel(0.1f, 0.1f, 0.1f), onePixel(0.f, 0.f, 0.f));
  EXPECT_NEAR(m.relMse, 1.0, 1e-6);
  EXPECT_NEAR(m.mape, 10.0, 1e-5);
}

// A mask keeps only its pixels: the means are over their channels, the rest ignored however wrong.
TEST(ErrorMetrics, AMaskAveragesOverItsPixelsOnly) {
  const Image image{3, 1, {1.f, 2.f, 0.f, 100.f, 100.f, 100.f, 0.5f, 0.5f, 0.5f}};
  const Image reference{3, 1, {1.f, 1.f, 0.5f, 0.f, 0.f, 0.f, 0.5f, 0.5f, 0.5f}};
  const ErrorMetrics m = errorMetrics(image, reference, PixelMask{1, 0, 1});
  EXPECT_DOUBLE_EQ(m.mse, (0.0 + 1.0 + 0.25 + 0.0 + 0.0 + 0.0) / 6.0);
  EXPECT_NEAR(m.relMse, (1.0 / 1.01 + 0.25 / 0.26) / 6.0, 1e-12);
  // The whole image's error is the masked-out pixel's.
  EXPECT_GT(errorMetrics(image, reference).relMse, 1000.0);
  EXPECT_EQ(errorMetrics(image, reference, PixelMask{0, 0, 1}).relMse, 0.0);
  EXPECT_THROW(errorMetrics(image, reference, PixelMask{1, 1}), std::invalid_argument);
  // The bias and variance split over the same pixels: here the two passes agree (no variance).
  EvenOddBuffers buffers(3, 1);
  buffers.addRunningMean(image);
  buffers.addRunningMean(image);
  const RelMseSplit split = splitRelMse(buffers, image, reference, PixelMask{1, 0, 1});
  EXPECT_NEAR(split.relMse, m.relMse, 1e-12);
  EXPECT_NEAR(split.variance, 0.0, 1e-12);
}

TEST(ErrorMetrics, SizeMismatchThrows) {
  EXPECT_THROW(errorMetrics(onePixel(0.f, 0.f, 0.f), Image{2, 1, std::vector<float>(6, 0.f)}), std::invalid_argument);
}

TEST(TwoBuffer, HandComputedEqualHalves) {
  // Passes 1, 3, 2, 6: A = mean(1, 2) = 1.5, B = mean(3, 6) = 4.5, Var(mean) = (A - B)² / 4 = 2.25;
  // the mean is 3, so relMSE = 2.25 / (9 + 0.01).
  EvenOddBuffers b(1, 1);
  for (double v : {1.0, 3.0, 2.0, 6.0}) b.addPass({v, v, v});
  EXPECT_EQ(b.passes(), 4u);
  EXPECT_DOUBLE_EQ(b.estimate().mse, 2.25);
  EXPECT_DOUBLE_EQ(b.estimate().relMse, 2.25 / 9.01);
}

TEST(TwoBuffer, HandComputedUnequalHalves) {
  // Passes 1, 3, 2: A = 1.5 (2 passes), B = 3 (1 pass), Var(mean) = (A - B)² · 2·1 / 3² = 0.5.
  EvenOddBuffers b(1, 1);
  for (double v : {1.0, 3.0, 2.0}) b.addPass({v, v, v});
  EXPECT_DOUBLE_EQ(b.estimate().mse, 0.5);
  EXPECT_DOUBLE_EQ(b.estimate().relMse, 0.5 / 4.01);
}

TEST(TwoBuffer, NothingBeforeTwoPasses) {
  EvenOddBuffers b(1, 1);
  EXPECT_EQ(b.estimate().mse, 0.0);
  b.addPass({1.0, 1.0, 1.0});
  EXPECT_EQ(b.estimate().mse, 0.0);
}

TEST(TwoBuffer, RunningMeansGiveThePassImages) {
  // The running means of passes 1, 3, 2, 6 are 1, 2, 2, 3.
  EvenOddBuffers fromMeans(1, 1);
  for (float m : {1.f, 2.f, 2.f, 3.f}) fromMeans.addRunningMean(onePixel(m, m, m));
  EXPECT_DOUBLE_EQ(fromMeans.estimate().mse, 2.25);
}

TEST(TwoBuffer, BuffersOfInterleavedPassesAddUpToOnesOfAll) {
  // Passes 1, 3, 2, 6 taken by two processes, pass indices 0, 2 and 1, 3 (PassSchedule), each
  // from its own running means (1, 1.5 and 3, 4.5): their sums added give HandComputedEqualHalves.
  EvenOddBuffers first(1, 1), second(1, 1);
  first.addRunningMean(onePixel(1.f, 1.f, 1.f), 0);
  first.addRunningMean(onePixel(1.5f, 1.5f, 1.5f), 2);
  second.addRunningMean(onePixel(3.f, 3.f, 3.f), 1);
  second.addRunningMean(onePixel(4.5f, 4.5f, 4.5f), 3);
  EXPECT_EQ(second.evenPasses(), 0u);
  EvenOddBuffers run(1, 1);
  for (const EvenOddBuffers* b : {&first, &second}) {
    for (size_t i = 0; i < 2; ++i)
      for (size_t j = 0; j < 3; ++j) run.sums()[i][j] += b->sums()[i][j];
    run.addForeignPasses(b->evenPasses(), b->oddPasses());
  }
  EXPECT_EQ(run.passes(), 4u);
  EXPECT_DOUBLE_EQ(run.estimate().mse, 2.25);
}

// Synthetic passes with known per-pass variance σ²: the estimate averages to σ²/n. Each pixel's
// (A - B)²/4 is (σ²/n)·χ²₁, so over P pixel-channels the mean has relative standard deviation
// sqrt(2/P); the tolerance is five of those.
TEST(TwoBuffer, EstimatesTheVarianceOfTheMean) {
  constexpr int kW = 100, kH = 100, kPasses = 8;
  constexpr double kSigma = 0.5, kMean = 2.0;
  std::mt19937_64 rng(42);
  std::normal_distribution<double> normal(kMean, kSigma);
  EvenOddBuffers b(kW, kH);
  for (int p = 0; p < kPasses; ++p) {
    std::vector<double> pass(3 * kW * kH);
    for (double& v : pass) v = normal(rng);
    b.addPass(pass);
  }
  const double expected = kSigma * kSigma / kPasses;
  const double tolerance = 5.0 * std::sqrt(2.0 / (3.0 * kW * kH)) * expected;
  EXPECT_NEAR(b.estimate().mse, expected, tolerance);
}

}  // namespace
}  // namespace pathlab
