// Running mean and standard error of a Monte Carlo estimator (Welford's update, in double).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

namespace pathlab::test {

struct MeanEstimate {
  double mean = 0.0, standardError = 0.0;
  uint64_t count = 0;
  double zScore(double expected) const { return (mean - expected) / standardError; }
};

class RunningStats {
 public:
  void add(double v) {
    ++n_;
    const double d = v - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (v - mean_);
  }
  double mean() const { return mean_; }
  double standardError() const {
    return n_ > 1 ? std::sqrt(m2_ / static_cast<double>(n_ - 1) / static_cast<double>(n_)) : 0.0;
  }
  MeanEstimate estimate() const { return {mean_, standardError(), n_}; }

 private:
  uint64_t n_ = 0;
  double mean_ = 0.0, m2_ = 0.0;
};

// The |zDifference| beyond which the mean tests fail: two-sided; with fixed seeds a failure is a
// real bias, not luck.
inline constexpr double kMaxZ = 4.0;

// (a - b) / sqrt(se_a^2 + se_b^2) of two independent estimates; 0 when both are exactly equal,
// +-inf when they differ with no standard error (two exact results that disagree).
inline double zDifference(const MeanEstimate& a, const MeanEstimate& b) {
  const double d = a.mean - b.mean;
  const double se = std::sqrt(a.standardError * a.standardError + b.standardError * b.standardError);
  if (se > 0.0) return d / se;
  if (d == 0.0) return 0.0;
  return d > 0.0 ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
}

}  // namespace pathlab::test
