// Drawing of the live error plot: axes from core/metrics/log_axis, series as polylines with markers.
#include "ui/panels/error_plot.h"

#include "core/metrics/log_axis.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab::ui {

namespace {

// Okabe and Ito's colour-blind-safe palette (as the SVG plots of `pathlab converge`), reordered
// and with light grey for black so every line reads on the dark background.
constexpr ImU32 kPalette[] = {IM_COL32(230, 159, 0, 255),   IM_COL32(86, 180, 233, 255), IM_COL32(0, 158, 115, 255),
                              IM_COL32(240, 228, 66, 255),  IM_COL32(204, 121, 167, 255), IM_COL32(213, 94, 0, 255),
                              IM_COL32(0, 114, 178, 255),   IM_COL32(221, 221, 221, 255)};

double xOf(const ErrorPoint& p, bool againstSpp) { return againstSpp ? static_cast<double>(p.spp) : p.seconds; }

void dashedLine(ImDrawList* draw, ImVec2 a, ImVec2 b, ImU32 colour, float dash, float thickness) {
  const float dx = b.x - a.x, dy = b.y - a.y, length = std::sqrt(dx * dx + dy * dy);
  if (!(length > 0.f)) return;
  for (float s = 0.f; s < length; s += 2.f * dash) {
    const float e = std::min(s + dash, length);
    draw->AddLine(ImVec2(a.x + dx * s / length, a.y + dy * s / length), ImVec2(a.x + dx * e / length, a.y + dy * e / length),
                  colour, thickness);
  }
}

}  // namespace

ImU32 seriesColour(int id) { return kPalette[static_cast<size_t>(std::max(id - 1, 0)) % std::size(kPalette)]; }

void drawErrorPlot(const std::vector<ErrorSeries>& series, const ErrorPlotOptions& o, ImVec2 size) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("##errorplot", ImVec2(std::max(size.x, 1.f), std::max(size.y, 1.f)));
  const bool hovered = ImGui::IsItemHovered();
  const float line = ImGui::GetTextLineHeight();
  const float s = o.uiScale;

  double xMin = std::numeric_limits<double>::max(), xMax = 0.0, yMin = std::numeric_limits<double>::max(), yMax = 0.0;
  for (const ErrorSeries& sr : series)
    for (const ErrorPoint& p : sr.points) {
      const double x = xOf(p, o.againstSpp), y = metricValue(p.error, o.metric);
      if (!(x > 0.0) || !(y > 0.0) || !std::isfinite(y)) continue;
      xMin = std::min(xMin, x), xMax = std::max(xMax, x);
      yMin = std::min(yMin, y), yMax = std::max(yMax, y);
    }
  const std::string xName = o.againstSpp ? "samples per pixel" : "render time (s)";
  draw->AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(20, 20, 24, 255), 3.f);
  if (xMax == 0.0) {
    const char* text = "no error yet: the first full pass against the reference gives the first point";
    draw->AddText(ImVec2(origin.x + 8.f * s, origin.y + 8.f * s), IM_COL32(160, 160, 160, 255), text);
    return;
  }
  const LogAxis ax = LogAxis::fit(xMin, xMax), ay = LogAxis::fit(yMin, yMax);
  // Small plots (640 x 480 windows) drop the title and the x label: the controls above say both.
  const bool compact = size.y < 9.f * line;
  // The legend (colour, label, newest value) goes right of the plot, never over the curves; where
  // that would leave the plot less than 55 % of the width, it shrinks to "id integrator value" (the
  // labels are in the tooltips and the CSV) and still stands beside it.
  std::vector<std::string> entries;
  float legendWidth = 0.f;
  const float swatch = 16.f * s, pad = 4.f * s;
  auto legendEntries = [&](bool full) {
    entries.clear();
    legendWidth = 0.f;
    for (const ErrorSeries& sr : series) {
      const std::string value = sr.points.empty() ? std::string("-")
                                                  : fmt::format("{:.3g}", metricValue(sr.points.back().error, o.metric));
      // Short: the integrator alone ("pt", "B: bpt"), enough to tell the sides apart.
      const size_t word = sr.label.find(' ', sr.label.starts_with("B: ") ? 3 : 0);
      const std::string shortLabel = sr.label.substr(0, word);
      entries.push_back(full ? fmt::format("{}: {}  {}", sr.id, sr.label, value)
                             : fmt::format("{} {}  {}", sr.id, shortLabel, value));
      legendWidth = std::max(legendWidth, ImGui::CalcTextSize(entries.back().c_str()).x);
    }
    return legendWidth + swatch + 4.f * pad;
  };
  float legendBlock = legendEntries(true);
  if (legendBlock > 0.45f * size.x) legendBlock = legendEntries(false);
  const float left = ImGui::CalcTextSize("0.0001").x + 10.f * s, right = 10.f * s + legendBlock;
  const float top = compact ? 6.f * s : line + 8.f * s, bottom = (compact ? 1.f : 2.f) * line + 8.f * s;
  const ImVec2 p0(origin.x + left, origin.y + top), p1(origin.x + size.x - right, origin.y + size.y - bottom);
  if (p1.x - p0.x < 20.f || p1.y - p0.y < 20.f) return;
  auto px = [&](double x) { return p0.x + static_cast<float>(ax.position(x)) * (p1.x - p0.x); };
  auto py = [&](double y) { return p1.y - static_cast<float>(ay.position(y)) * (p1.y - p0.y); };

  // Title, grid, ticks, labels.
  const std::string title = fmt::format("{} against {}", errorMetricName(o.metric), xName);
  if (!compact) draw->AddText(ImVec2(p0.x, origin.y + 4.f * s), IM_COL32(230, 230, 230, 255), title.c_str());
  const ImU32 grid = IM_COL32(70, 70, 78, 255), tick = IM_COL32(150, 150, 150, 255), text = IM_COL32(190, 190, 190, 255);
  for (const LogTick& t : ax.ticks()) {
    const float x = px(t.value);
    if (t.major) draw->AddLine(ImVec2(x, p0.y), ImVec2(x, p1.y), grid);
    draw->AddLine(ImVec2(x, p1.y), ImVec2(x, p1.y - (t.major ? 6.f : 3.f) * s), tick);
    if (!t.label.empty()) {
      const float w = ImGui::CalcTextSize(t.label.c_str()).x;
      draw->AddText(ImVec2(x - 0.5f * w, p1.y + 3.f * s), text, t.label.c_str());
    }
  }
  // Labels at 2 and 5 only where a decade is tall enough for three labels.
  const float decadeHeight = (p1.y - p0.y) / static_cast<float>(std::max(1.0, std::log10(ay.hi() / ay.lo())));
  for (const LogTick& t : ay.ticks()) {
    const float y = py(t.value);
    if (t.major) draw->AddLine(ImVec2(p0.x, y), ImVec2(p1.x, y), grid);
    draw->AddLine(ImVec2(p0.x, y), ImVec2(p0.x + (t.major ? 6.f : 3.f) * s, y), tick);
    if (!t.label.empty() && (t.major || decadeHeight > 3.5f * line)) {
      const ImVec2 e = ImGui::CalcTextSize(t.label.c_str());
      draw->AddText(ImVec2(p0.x - e.x - 4.f * s, y - 0.5f * e.y), text, t.label.c_str());
    }
  }
  draw->AddRect(p0, p1, tick);
  const float xw = ImGui::CalcTextSize(xName.c_str()).x;
  if (!compact) draw->AddText(ImVec2(0.5f * (p0.x + p1.x - xw), p1.y + line + 4.f * s), text, xName.c_str());

  draw->PushClipRect(p0, p1, true);
  // The Monte Carlo rate through the first point of the newest series: error ∝ 1/t (relMSE) or
  // 1/sqrt(t) (RMSE, MAPE). A curve parallel to it converges at the rate; a flatter one is
  // dominated by rare large samples (or bias), a steeper one is still leaving its warm-up.
  if (o.slope && !series.empty() && !series.back().points.empty()) {
    const ErrorPoint& first = series.back().points.front();
    const double x0 = xOf(first, o.againstSpp), y0 = metricValue(first.error, o.metric);
    if (x0 > 0.0 && y0 > 0.0) {
      const double slope = monteCarloSlope(o.metric);
      const double x1 = ax.hi();
      const double y1 = y0 * std::pow(x1 / x0, slope);
      dashedLine(draw, ImVec2(px(x0), py(y0)), ImVec2(px(x1), py(y1)), IM_COL32(200, 200, 200, 150), 6.f * s, 1.5f * s);
      const std::string label = fmt::format("{} 1/{}", "~", slope < -0.75 ? (o.againstSpp ? "N" : "t")
                                                                            : (o.againstSpp ? "sqrt(N)" : "sqrt(t)"));
      // At the line's right end, below it: clear of the curves, which start at the left.
      const float lw = ImGui::CalcTextSize(label.c_str()).x;
      draw->AddText(ImVec2(p1.x - lw - 4.f * s, std::min(py(y1) + 3.f * s, p1.y - line - 2.f * s)),
                    IM_COL32(200, 200, 200, 220), label.c_str());
    }
  }
  // Series, oldest first so the running one is drawn on top.
  float bestDistance = 10.f * s;
  const ErrorSeries* bestSeries = nullptr;
  const ErrorPoint* bestPoint = nullptr;
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  std::vector<ImVec2> points;
  for (const ErrorSeries& sr : series) {
    points.clear();
    for (const ErrorPoint& p : sr.points) {
      const double x = xOf(p, o.againstSpp), y = metricValue(p.error, o.metric);
      if (!(x > 0.0) || !(y > 0.0) || !std::isfinite(y)) continue;
      points.emplace_back(px(x), py(y));
      if (hovered) {
        const float d = std::hypot(points.back().x - mouse.x, points.back().y - mouse.y);
        if (d < bestDistance) bestDistance = d, bestSeries = &sr, bestPoint = &p;
      }
    }
    const ImU32 colour = seriesColour(sr.id);
    const bool newest = &sr == &series.back();
    if (points.size() > 1) draw->AddPolyline(points.data(), static_cast<int>(points.size()), colour, 0, (newest ? 2.5f : 1.8f) * s);
    for (const ImVec2& p : points) draw->AddCircleFilled(p, 2.2f * s, colour);
  }
  draw->PopClipRect();

  // The legend beside the plot, from its top.
  const ImVec2 l0(p1.x + pad, p0.y);
  const ImVec2 l1(l0.x + legendWidth + swatch + 3.f * pad,
                  std::min(origin.y + size.y - pad, l0.y + static_cast<float>(entries.size()) * line + 2.f * pad));
  draw->AddRectFilled(l0, l1, IM_COL32(10, 10, 12, 200), 3.f);
  draw->PushClipRect(l0, l1, true);
  for (size_t i = 0; i < entries.size(); ++i) {
    const float y = l0.y + pad + static_cast<float>(i) * line;
    draw->AddLine(ImVec2(l0.x + pad, y + 0.5f * line), ImVec2(l0.x + pad + swatch, y + 0.5f * line), seriesColour(series[i].id),
                  2.5f * s);
    draw->AddText(ImVec2(l0.x + 2.f * pad + swatch, y), IM_COL32(230, 230, 230, 255), entries[i].c_str());
  }
  draw->PopClipRect();

  if (bestPoint)
    ImGui::SetTooltip("%d: %s\n%.3g s, %llu spp\nrelMSE %.4g   RMSE %.4g   MAPE %.4g", bestSeries->id,
                      bestSeries->label.c_str(), bestPoint->seconds, static_cast<unsigned long long>(bestPoint->spp),
                      bestPoint->error.relMse, bestPoint->error.rmse, bestPoint->error.mape);
}

}  // namespace pathlab::ui
