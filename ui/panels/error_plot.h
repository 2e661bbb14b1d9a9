// The live log-log plot of error against render time or samples per pixel, drawn with ImGui's
// draw list (ImPlot is not in Debian): one line per error series, a legend, the Monte Carlo
// rate as a dashed reference slope, and the nearest point under the mouse in a tooltip.
#pragma once

#include "core/converge/error_tracker.h"

#include <imgui.h>

#include <vector>

namespace pathlab::ui {

struct ErrorPlotOptions {
  ErrorMetric metric = ErrorMetric::RelMse;
  bool againstSpp = false;  // x: samples per pixel instead of render seconds
  bool slope = true;        // the reference slope through the newest series' first point
  float uiScale = 1.f;
};

// Colour of a series, by its id so a run keeps its colour while older ones are dropped.
ImU32 seriesColour(int id);

// Draws at the cursor and advances it by `size`.
void drawErrorPlot(const std::vector<ErrorSeries>& series, const ErrorPlotOptions& options, ImVec2 size);

}  // namespace pathlab::ui
