// Discrete distribution over indices proportional to non-negative weights (light selection).
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace pathlab {

class Distribution1D {
 public:
  Distribution1D() = default;
  explicit Distribution1D(const std::vector<double>& weights) {
    cdf_.resize(weights.size() + 1, 0.0);
    for (size_t i = 0; i < weights.size(); ++i) cdf_[i + 1] = cdf_[i] + std::max(weights[i], 0.0);
    total_ = cdf_.back();
    if (total_ > 0.0)
      for (double& c : cdf_) c /= total_;
  }
  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  float pmf(size_t i) const { return i < size() ? static_cast<float>(cdf_[i + 1] - cdf_[i]) : 0.f; }

  // Returns the index for u in [0,1); `uRemapped` receives u rescaled to [0,1) within the bin.
  size_t sample(float u, float* pmfOut = nullptr, float* uRemapped = nullptr) const {
    const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), static_cast<double>(u));
    size_t i = std::min(static_cast<size_t>(it - cdf_.begin()) - 1, size() - 1);
    while (i > 0 && cdf_[i + 1] == cdf_[i]) --i;  // never return a zero-weight bin
    const double w = cdf_[i + 1] - cdf_[i];
    if (pmfOut) *pmfOut = static_cast<float>(w);
    if (uRemapped)
      *uRemapped = w > 0 ? std::min(static_cast<float>((u - cdf_[i]) / w), 0x1.fffffep-1f) : 0.f;
    return i;
  }

 private:
  std::vector<double> cdf_;
  double total_ = 0.0;
};

}  // namespace pathlab
