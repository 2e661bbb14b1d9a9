// Log-scaled plot axes, as plain logic shared by the SVG plots of `pathlab converge`
// (loglog_plot) and the viewer's live error plot: the range spans whole decades around the data,
// with labels at the decades and
// minor ticks at 2..9 times each; when the data span less than a decade, labelled ticks at 1, 2
// and 5 times each decade keep the axis readable.
#pragma once

#include <string>
#include <vector>

namespace pathlab {

struct LogTick {
  double value = 0.0;
  bool major = false;  // labelled
  std::string label;
};

class LogAxis {
 public:
  LogAxis() = default;
  // The smallest range of whole decades holding [lo, hi] (lo, hi > 0), at least one decade.
  static LogAxis fit(double lo, double hi);
  double lo() const { return lo_; }
  double hi() const { return hi_; }
  int loDecade() const { return loDecade_; }  // lo() = 10^loDecade()
  int hiDecade() const { return hiDecade_; }
  // Position in [0, 1] of a value (outside the range: outside [0, 1]).
  double position(double value) const;
  std::vector<LogTick> ticks() const;

 private:
  int loDecade_ = 0, hiDecade_ = 1;
  double lo_ = 1.0, hi_ = 10.0;
};

// "0.01", "0.5", "1", "20", "1000", "1e-5", "2e6": short labels for ticks and the colour bar.
std::string tickLabel(double value);

}  // namespace pathlab
