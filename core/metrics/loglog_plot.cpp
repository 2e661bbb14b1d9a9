// SVG output of log-log plots: the axes span whole decades around the data.
#include "core/metrics/loglog_plot.h"

#include "core/metrics/log_axis.h"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace pathlab {

namespace {

constexpr double kWidth = 700, kHeight = 420;
constexpr double kLeft = 70, kRight = 250, kTop = 36, kBottom = 56;  // margins; the legend sits right
// Colour-blind-safe palette (Okabe and Ito 2008), then repeated with dashes.
constexpr std::array<const char*, 8> kColours = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                 "#E69F00", "#56B4E9", "#000000", "#F0E442"};

std::string escapeXml(const std::string& s) {
  std::string out;
  for (char c : s) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  return out;
}

// "10" with a superscript exponent; 0.01 .. 1000 are written out, which reads better for seconds.
std::string decadeLabel(int e, double x, double y, const char* anchor) {
  if (e >= -2 && e <= 3) {
    const std::string text = e >= 0 ? fmt::format("{}", static_cast<long>(std::pow(10.0, e))) : fmt::format("{:.{}f}", std::pow(10.0, e), -e);
    return fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="{}">{}</text>)", x, y, anchor, text);
  }
  return fmt::format(R"(<text x="{:.1f}" y="{:.1f}" text-anchor="{}">10<tspan dy="-6" font-size="9">{}</tspan></text>)",
                     x, y, anchor, e);
}

// Decade exponents of an axis: the grid and labels are drawn at 10^lo .. 10^hi.
struct Decades {
  int lo, hi;
};

}  // namespace

std::string renderSvg(const LogLogPlot& plot) {
  double xMin = std::numeric_limits<double>::max(), xMax = 0, yMin = std::numeric_limits<double>::max(), yMax = 0;
  for (const PlotSeries& s : plot.series)
    for (const auto& [x, y] : s.points)
      if (x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y)) {
        xMin = std::min(xMin, x), xMax = std::max(xMax, x);
        yMin = std::min(yMin, y), yMax = std::max(yMax, y);
      }
  if (xMax == 0) throw std::invalid_argument("nothing to plot: no positive point");
  const LogAxis ax = LogAxis::fit(xMin, xMax), ay = LogAxis::fit(yMin, yMax);
  const Decades dx{ax.loDecade(), ax.hiDecade()}, dy{ay.loDecade(), ay.hiDecade()};
  const double plotW = kWidth - kLeft - kRight, plotH = kHeight - kTop - kBottom;
  auto px = [&](double x) { return kLeft + ax.position(x) * plotW; };
  auto py = [&](double y) { return kTop + plotH - ay.position(y) * plotH; };

  std::string svg = fmt::format(
      R"(<?xml version="1.0" encoding="UTF-8"?>
<svg xmlns="http://www.w3.org/2000/svg" width="{0}" height="{1}" viewBox="0 0 {0} {1}" font-family="sans-serif" font-size="12">
<rect width="{0}" height="{1}" fill="white"/>
<text x="{2:.1f}" y="22" text-anchor="middle" font-size="14">{3}</text>
)",
      kWidth, kHeight, kLeft + plotW / 2, escapeXml(plot.title));

  // Grid and ticks: a line and label at every decade, short ticks at 2..9 times each decade.
  svg += R"(<g stroke="#ddd">)";
  for (int e = dx.lo; e <= dx.hi; ++e) svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}"/>)", px(std::pow(10.0, e)), kTop, kTop + plotH);
  for (int e = dy.lo; e <= dy.hi; ++e) svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}"/>)", kLeft, py(std::pow(10.0, e)), kLeft + plotW);
  svg += "</g>\n<g stroke=\"black\">";
  for (int e = dx.lo; e < dx.hi; ++e)
    for (int m = 2; m <= 9; ++m) {
      const double x = px(m * std::pow(10.0, e));
      svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{0:.1f}" y2="{2:.1f}"/>)", x, kTop + plotH, kTop + plotH - 4);
    }
  for (int e = dy.lo; e < dy.hi; ++e)
    for (int m = 2; m <= 9; ++m) {
      const double y = py(m * std::pow(10.0, e));
      svg += fmt::format(R"(<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}"/>)", kLeft, y, kLeft + 4);
    }
  svg += fmt::format(R"(<rect x="{:.1f}" y="{:.1f}" width="{:.1f}" height="{:.1f}" fill="none"/>)", kLeft, kTop, plotW, plotH);
  svg += "</g>\n";
  for (int e = dx.lo; e <= dx.hi; ++e) svg += decadeLabel(e, px(std::pow(10.0, e)), kTop + plotH + 24, "middle");
  for (int e = dy.lo; e <= dy.hi; ++e) svg += decadeLabel(e, kLeft - 8, py(std::pow(10.0, e)) + 4, "end");
  svg += fmt::format(R"svg(
<text x="{:.1f}" y="{:.1f}" text-anchor="middle">{}</text>
<text transform="translate(16 {:.1f}) rotate(-90)" text-anchor="middle">{}</text>
)svg",
                     kLeft + plotW / 2, kHeight - 12, escapeXml(plot.xLabel), kTop + plotH / 2, escapeXml(plot.yLabel));

  // One polyline per series, then its legend entry.
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const PlotSeries& s = plot.series[i];
    const char* colour = kColours[i % kColours.size()];
    const char* dash = i >= kColours.size() ? R"( stroke-dasharray="6 3")" : "";
    std::string points;
    for (const auto& [x, y] : s.points)
      if (x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y))
        points += fmt::format("{}{:.1f},{:.1f}", points.empty() ? "" : " ", px(x), py(y));
    svg += fmt::format(R"(<polyline fill="none" stroke="{}" stroke-width="2"{} points="{}"><title>{}</title></polyline>)",
                       colour, dash, points, escapeXml(s.label));
    const double ly = kTop + 8 + 18 * static_cast<double>(i);
    svg += fmt::format(R"(
<line x1="{0:.1f}" y1="{1:.1f}" x2="{2:.1f}" y2="{1:.1f}" stroke="{3}" stroke-width="2"{4}/><text x="{5:.1f}" y="{6:.1f}">{7}</text>
)",
                       kLeft + plotW + 12, ly, kLeft + plotW + 36, colour, dash, kLeft + plotW + 42, ly + 4,
                       escapeXml(s.label));
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace pathlab
