// Per-pixel error images against hand-computed values; their mean is the image's relMSE.
#include "core/metrics/error_image.h"
#include "core/metrics/error_metrics.h"

#include <gtest/gtest.h>

#include <numeric>

namespace pathlab {
namespace {

TEST(ErrorImage, HandComputedValues) {
  // Two pixels: (1, 2, 3) against (1, 1, 1), and (0, 0, 0) against (0.1, 0, 0).
  const Image image{2, 1, {1.f, 2.f, 3.f, 0.f, 0.f, 0.f}};
  const Image reference{2, 1, {1.f, 1.f, 1.f, 0.1f, 0.f, 0.f}};
  const std::vector<float> rel = pixelErrors(image, reference, PixelError::RelativeSquared);
  ASSERT_EQ(rel.size(), 2u);
  EXPECT_NEAR(rel[0], (0.0 + 1.0 / 1.01 + 4.0 / 1.01) / 3.0, 1e-6);
  EXPECT_NEAR(rel[1], (0.01 / (0.01 + 0.01)) / 3.0, 1e-6);
  const std::vector<float> abs = pixelErrors(image, reference, PixelError::Absolute);
  EXPECT_NEAR(abs[0], 1.0, 1e-6);
  EXPECT_NEAR(abs[1], 0.1 / 3.0, 1e-6);
  // The mean of the relative squared error image is relMSE.
  const double mean = std::accumulate(rel.begin(), rel.end(), 0.0) / static_cast<double>(rel.size());
  EXPECT_NEAR(mean, errorMetrics(image, reference).relMse, 1e-6);
  EXPECT_EQ(pixelErrors(reference, reference, PixelError::RelativeSquared), std::vector<float>(2, 0.f));
}

TEST(ErrorImage, SizesMustMatch) {
  const Image a{2, 1, std::vector<float>(6, 1.f)}, b{1, 2, std::vector<float>(6, 1.f)};
  try {
    pixelErrors(a, b, PixelError::Absolute);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("2 x 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 x 2"), std::string::npos) << e.what();
  }
}

TEST(ErrorImage, QuantilesOfThePositiveValues) {
  std::vector<float> v;
  for (int i = 0; i <= 100; ++i) v.push_back(static_cast<float>(i));
  v.push_back(std::numeric_limits<float>::quiet_NaN());
  v.push_back(-5.f);
  const auto [lo, hi] = positiveQuantiles(v, 0.0, 1.0);
  EXPECT_EQ(lo, 1.f);  // 0 is not positive
  EXPECT_EQ(hi, 100.f);
  const auto [q10, q90] = positiveQuantiles(v, 0.1, 0.9);
  EXPECT_NEAR(q10, 10.9f, 1.f);
  EXPECT_NEAR(q90, 90.1f, 1.f);
  EXPECT_EQ(positiveQuantiles({0.f, -1.f}, 0.0, 1.0), std::make_pair(0.f, 0.f));
}

}  // namespace
}  // namespace pathlab
