// Per-pixel error images (definitions in the header).
#include "core/metrics/error_image.h"

#include "core/metrics/error_metrics.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlab {

const char* pixelErrorName(PixelError kind) {
  return kind == PixelError::RelativeSquared ? "relative squared error" : "absolute error";
}

std::vector<float> pixelErrors(const Image& image, const Image& reference, PixelError kind) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument(fmt::format("the image is {} x {} but the reference is {} x {}", image.width,
                                            image.height, reference.width, reference.height));
  std::vector<float> out(image.rgb.size() / 3);
  for (size_t p = 0; p < out.size(); ++p) {
    double sum = 0.0;
    for (size_t c = 0; c < 3; ++c) {
      const double x = image.rgb[3 * p + c], r = reference.rgb[3 * p + c], d = x - r;
      sum += kind == PixelError::RelativeSquared ? d * d / (r * r + kRelMseEpsilon) : std::abs(d);
    }
    out[p] = static_cast<float>(sum / 3.0);
  }
  return out;
}

std::pair<float, float> positiveQuantiles(std::vector<float> values, double lo, double hi) {
  std::erase_if(values, [](float v) { return !(v > 0.f) || !std::isfinite(v); });
  if (values.empty()) return {0.f, 0.f};
  auto at = [&](double q) {
    const size_t i = std::min(values.size() - 1, static_cast<size_t>(std::clamp(q, 0.0, 1.0) * static_cast<double>(values.size() - 1)));
    std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
    return values[i];
  };
  const float a = at(lo), b = at(hi);
  return {a, b};
}

}  // namespace pathlab
