// Error metrics and the even/odd two-buffer variance estimate (formulas in the header).
#include "core/metrics/error_metrics.h"

#include <fmt/core.h>

#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

void checkMask(const PixelMask& mask, size_t values) {
  if (!mask.empty() && 3 * mask.size() != values)
    throw std::invalid_argument(fmt::format("a mask of {} pixels for an image of {}", mask.size(), values / 3));
}

bool masked(const PixelMask& mask, size_t value) { return mask.empty() || mask[value / 3] != 0; }

}  // namespace

ErrorMetrics errorMetrics(const Image& image, const Image& reference, const PixelMask& mask) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument(fmt::format("the image is {} x {} but the reference is {} x {}", image.width,
                                            image.height, reference.width, reference.height));
  checkMask(mask, image.rgb.size());
  ErrorMetrics m;
  const size_t n = image.rgb.size();
  double se = 0.0, rel = 0.0, ape = 0.0;
  size_t counted = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!masked(mask, i)) continue;
    ++counted;
    const double x = image.rgb[i], r = reference.rgb[i];
    const double d = x - r;
    se += d * d;
    rel += d * d / (r * r + kRelMseEpsilon);
    ape += std::abs(d) / (std::abs(r) + kMapeEpsilon);
  }
  if (counted == 0) return m;
  const double count = static_cast<double>(counted);
  m.mse = se / count;
  m.rmse = std::sqrt(m.mse);
  m.relMse = rel / count;
  m.mape = ape / count;
  return m;
}

EvenOddBuffers::EvenOddBuffers(int width, int height)
    : width_(width),
      height_(height),
      even_(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.0),
      odd_(even_.size(), 0.0),
      previousMean_(even_.size(), 0.0) {}

void EvenOddBuffers::addPass(const std::vector<double>& passRgb) { addPass(passRgb, passes()); }

void EvenOddBuffers::addPass(const std::vector<double>& passRgb, uint64_t passIndex) {
  if (passRgb.size() != even_.size())
    throw std::invalid_argument(fmt::format("a pass image of {} values for a {} x {} film", passRgb.size(), width_, height_));
  const bool isEven = passIndex % 2 == 0;
  std::vector<double>& sum = isEven ? even_ : odd_;
  for (size_t i = 0; i < sum.size(); ++i) sum[i] += passRgb[i];
  ++(isEven ? evenPasses_ : oddPasses_);
}

void EvenOddBuffers::addRunningMean(const Image& mean) { addRunningMean(mean, passes()); }

void EvenOddBuffers::addRunningMean(const Image& mean, uint64_t passIndex) {
  if (mean.width != width_ || mean.height != height_)
    throw std::invalid_argument(fmt::format("a {} x {} image for a {} x {} film", mean.width, mean.height, width_, height_));
  const double n = static_cast<double>(passes() + 1);
  std::vector<double> pass(even_.size());
  for (size_t i = 0; i < pass.size(); ++i) {
    const double m = mean.rgb[i];
    pass[i] = n * m - (n - 1.0) * previousMean_[i];
    previousMean_[i] = m;
  }
  addPass(pass, passIndex);
}

TwoBufferEstimate EvenOddBuffers::estimate() const {
  TwoBufferEstimate e;
  if (evenPasses_ == 0 || oddPasses_ == 0 || even_.empty()) return e;
  const double mA = static_cast<double>(evenPasses_), mB = static_cast<double>(oddPasses_), n = mA + mB;
  const double scale = mA * mB / (n * n);
  double se = 0.0, rel = 0.0;
  for (size_t i = 0; i < even_.size(); ++i) {
    const double a = even_[i] / mA, b = odd_[i] / mB;
    const double var = (a - b) * (a - b) * scale;
    const double mean = (even_[i] + odd_[i]) / n;
    se += var;
    rel += var / (mean * mean + kRelMseEpsilon);
  }
  const double count = static_cast<double>(even_.size());
  e.mse = se / count;
  e.relMse = rel / count;
  return e;
}

double EvenOddBuffers::varianceOfMean(size_t i) const {
  if (evenPasses_ == 0 || oddPasses_ == 0) return 0.0;
  const double mA = static_cast<double>(evenPasses_), mB = static_cast<double>(oddPasses_), n = mA + mB;
  const double d = even_[i] / mA - odd_[i] / mB;
  return d * d * mA * mB / (n * n);
}

RelMseSplit splitRelMse(const EvenOddBuffers& buffers, const Image& mean, const Image& reference,
                        const PixelMask& mask) {
  if (mean.width != reference.width || mean.height != reference.height || mean.width != buffers.width() ||
      mean.height != buffers.height())
    throw std::invalid_argument(fmt::format("the split of relMSE: the image is {} x {}, the reference {} x {}, the buffers {} x {}",
                                            mean.width, mean.height, reference.width, reference.height, buffers.width(),
                                            buffers.height()));
  checkMask(mask, mean.rgb.size());
  RelMseSplit split;
  const size_t n = mean.rgb.size();
  double rel = 0.0, variance = 0.0;
  size_t counted = 0;
  for (size_t i = 0; i < n; ++i) {
    if (!masked(mask, i)) continue;
    ++counted;
    const double r = reference.rgb[i], d = static_cast<double>(mean.rgb[i]) - r, norm = r * r + kRelMseEpsilon;
    rel += d * d / norm;
    variance += buffers.varianceOfMean(i) / norm;
  }
  if (counted == 0) return split;
  split.relMse = rel / static_cast<double>(counted);
  split.variance = variance / static_cast<double>(counted);
  split.bias2 = split.relMse - split.variance;
  return split;
}

}  // namespace pathlab
