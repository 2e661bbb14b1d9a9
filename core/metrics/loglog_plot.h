// A log-log line plot written as a small standalone SVG (no dependency): decade ticks with
// labels, minor ticks at 2..9, one polyline per series and a legend.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pathlab {

struct PlotSeries {
  std::string label;
  std::vector<std::pair<double, double>> points;  // (x, y); points with x <= 0 or y <= 0 are skipped
};

struct LogLogPlot {
  std::string title;
  std::string xLabel, yLabel;
  std::vector<PlotSeries> series;
};

// Throws std::invalid_argument when no series has a positive point.
std::string renderSvg(const LogLogPlot& plot);

}  // namespace pathlab
