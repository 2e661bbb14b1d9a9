// Piecewise-constant densities on [0,1) and [0,1)^2, sampled by inverting their CDFs: a marginal
// over rows and one conditional per row (pbrt-v3 sec. 13.6.7, Distribution1D / Distribution2D).
// Used by the environment light to sample its map in proportion to radiance x sin(theta).
#pragma once

#include "core/math/types.h"

#include <vector>

namespace pathlab {

// A density on [0,1) proportional to n non-negative cell values.
class PiecewiseConstant1D {
 public:
  PiecewiseConstant1D() = default;
  explicit PiecewiseConstant1D(std::vector<float> values);

  size_t size() const { return values_.size(); }
  // Integral of the (unnormalised) step function over [0,1): the mean of the values.
  double integral() const { return integral_; }
  // x in [0,1) with density value(x) / integral(); `cell` receives the index of its cell.
  float sample(float u, float* pdf, size_t* cell) const;
  float pdf(size_t cell) const {
    return integral_ > 0.0 ? static_cast<float>(values_[cell] / integral_) : 0.f;
  }

 private:
  std::vector<float> values_;
  std::vector<double> cdf_;  // n + 1 entries, cdf_[n] = 1
  double integral_ = 0.0;
};

// A density on [0,1)^2 proportional to a grid of non-negative values (row-major, `width` a row):
// p(u, v) = value(u, v) / mean. Rows are v, columns u.
class PiecewiseConstant2D {
 public:
  PiecewiseConstant2D() = default;
  PiecewiseConstant2D(const std::vector<float>& values, int width, int height);

  double integral() const { return marginal_.integral(); }
  // (u, v) with density pdf(u, v); *pdf receives it (0 when every value is zero).
  Vec2 sample(Vec2 u, float* pdf) const;
  float pdf(Vec2 uv) const;

 private:
  int width_ = 0, height_ = 0;
  std::vector<PiecewiseConstant1D> rows_;  // p(u | v)
  PiecewiseConstant1D marginal_;           // p(v)
};

}  // namespace pathlab
