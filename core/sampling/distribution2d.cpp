// Piecewise-constant 1D and 2D densities: CDF construction and inversion.
#include "core/sampling/distribution2d.h"

#include <algorithm>

namespace pathlab {

PiecewiseConstant1D::PiecewiseConstant1D(std::vector<float> values) : values_(std::move(values)) {
  const size_t n = values_.size();
  cdf_.assign(n + 1, 0.0);
  for (size_t i = 0; i < n; ++i) {
    values_[i] = std::max(values_[i], 0.f);
    cdf_[i + 1] = cdf_[i] + static_cast<double>(values_[i]) / static_cast<double>(n);
  }
  integral_ = cdf_[n];
  if (integral_ > 0.0) {
    for (double& c : cdf_) c /= integral_;
  } else {
    // Every value zero: a uniform CDF keeps sample() defined; pdf() is still zero.
    for (size_t i = 0; i <= n; ++i) cdf_[i] = static_cast<double>(i) / static_cast<double>(n);
  }
  cdf_[n] = 1.0;
}

float PiecewiseConstant1D::sample(float u, float* pdf, size_t* cell) const {
  const size_t n = values_.size();
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), static_cast<double>(u));
  size_t i = std::min(static_cast<size_t>(it - cdf_.begin()) - 1, n - 1);
  while (i > 0 && cdf_[i + 1] == cdf_[i]) --i;  // never a zero-width cell
  const double width = cdf_[i + 1] - cdf_[i];
  const double du = width > 0.0 ? (static_cast<double>(u) - cdf_[i]) / width : 0.0;
  if (pdf) *pdf = this->pdf(i);
  if (cell) *cell = i;
  const double x = (static_cast<double>(i) + std::clamp(du, 0.0, 1.0)) / static_cast<double>(n);
  return std::min(static_cast<float>(x), kOneMinusEpsilon);
}

PiecewiseConstant2D::PiecewiseConstant2D(const std::vector<float>& values, int width, int height)
    : width_(width), height_(height) {
  rows_.reserve(static_cast<size_t>(height));
  std::vector<float> rowIntegrals(static_cast<size_t>(height));
  for (int y = 0; y < height; ++y) {
    const auto begin = values.begin() + static_cast<std::ptrdiff_t>(y) * width;
    rows_.emplace_back(std::vector<float>(begin, begin + width));
    rowIntegrals[static_cast<size_t>(y)] = static_cast<float>(rows_.back().integral());
  }
  marginal_ = PiecewiseConstant1D(std::move(rowIntegrals));
}

// p(u, v) = p(v) p(u | v) = (I_row / I) (f / I_row) = f / I (pbrt-v3 eq. 13.10).
Vec2 PiecewiseConstant2D::sample(Vec2 u, float* pdf) const {
  float pdfV = 0.f, pdfU = 0.f;
  size_t row = 0;
  const float v = marginal_.sample(u.y, &pdfV, &row);
  const float x = rows_[row].sample(u.x, &pdfU, nullptr);
  if (pdf) *pdf = pdfV * pdfU;
  return {x, v};
}

float PiecewiseConstant2D::pdf(Vec2 uv) const {
  const int x = std::clamp(static_cast<int>(uv.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  return marginal_.pdf(static_cast<size_t>(y)) * rows_[static_cast<size_t>(y)].pdf(static_cast<size_t>(x));
}

}  // namespace pathlab
