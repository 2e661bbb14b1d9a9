// Log axes: decade ranges, tick positions and labels.
#include "core/metrics/log_axis.h"

#include <fmt/core.h>

#include <cmath>

namespace pathlab {

LogAxis LogAxis::fit(double lo, double hi) {
  LogAxis a;
  if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) return a;
  if (hi < lo) std::swap(lo, hi);
  a.loDecade_ = static_cast<int>(std::floor(std::log10(lo) + 1e-9));
  a.hiDecade_ = static_cast<int>(std::ceil(std::log10(hi) - 1e-9));
  if (a.hiDecade_ <= a.loDecade_) a.hiDecade_ = a.loDecade_ + 1;
  a.lo_ = std::pow(10.0, a.loDecade_);
  a.hi_ = std::pow(10.0, a.hiDecade_);
  return a;
}

double LogAxis::position(double value) const {
  if (!(value > 0.0)) return -1.0;
  return (std::log10(value) - loDecade_) / static_cast<double>(hiDecade_ - loDecade_);
}

std::vector<LogTick> LogAxis::ticks() const {
  std::vector<LogTick> out;
  const int decades = hiDecade_ - loDecade_;
  // Few decades: label 2 and 5 too. Many: label every other decade so labels never collide.
  const int labelEvery = decades > 6 ? 2 : 1;
  for (int e = loDecade_; e <= hiDecade_; ++e) {
    const double base = std::pow(10.0, e);
    const bool labelled = (e - loDecade_) % labelEvery == 0 || e == hiDecade_;
    out.push_back({base, true, labelled ? tickLabel(base) : std::string()});
    if (e == hiDecade_) break;
    for (int m = 2; m <= 9; ++m) {
      const bool label = decades <= 2 && (m == 2 || m == 5);
      out.push_back({m * base, false, label ? tickLabel(m * base) : std::string()});
    }
  }
  return out;
}

std::string tickLabel(double v) {
  if (!(v > 0.0)) return "0";
  const double e = std::log10(v);
  if (e >= -2.0 - 1e-9 && e < 4.0) {
    const int digits = std::max(0, static_cast<int>(std::ceil(-e - 1e-9)));
    return fmt::format("{:.{}f}", v, digits);
  }
  // "1e-4", "2e6": the exponent without its padding, so neighbouring labels fit.
  const int exponent = static_cast<int>(std::floor(e + 1e-9));
  const long mantissa = std::lround(v / std::pow(10.0, exponent));
  if (mantissa >= 10) return fmt::format("1e{}", exponent + 1);
  return fmt::format("{}e{}", mantissa, exponent);
}

}  // namespace pathlab
