// The convergence panel along the bottom: the live error plot of every kept run (error against
// render time or samples per pixel) and the per-technique table of rays and time.
#include "ui/panels/panels.h"

#include "core/metrics/technique_table.h"
#include "ui/panels/error_plot.h"

#include <imgui.h>

#include <algorithm>

namespace pathlab::ui {

float convergencePanelHeight(float windowHeight, float uiScale) {
  // A third of the window, but room for a readable plot in small windows (640 x 480).
  return std::clamp(0.36f * windowHeight, std::min(200.f * uiScale, 0.45f * windowHeight), 360.f * uiScale);
}

void drawConvergenceWindow(ConvergenceState& convergence, ReferenceState& reference, const RenderSnapshot& snapshot,
                           PanelRect rect, float uiScale, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(rect.x, rect.y));
  ImGui::SetNextWindowSize(ImVec2(rect.width, rect.height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                                 ImGuiWindowFlags_NoScrollbar;
  if (!ImGui::Begin("Convergence (P)", &convergence.show, flags)) {
    ImGui::End();
    return;
  }
  const bool sideBySide = rect.width >= 820.f * uiScale;
  auto plotControls = [&] {
    int metric = static_cast<int>(convergence.metric);
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("relMSE").x + ImGui::GetFrameHeight() + 12.f * uiScale);
    if (ImGui::Combo("##metric", &metric, "relMSE\0RMSE\0MAPE\0")) convergence.metric = static_cast<ErrorMetric>(metric);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("relMSE: mean (x - r)^2 / (r^2 + 0.01)\nRMSE: sqrt(mean (x - r)^2)\nMAPE: mean |x - r| / (|r| + 0.01)");
    ImGui::SameLine();
    int axis = convergence.againstSpp ? 1 : 0;
    ImGui::RadioButton("time", &axis, 0);
    ImGui::SameLine();
    ImGui::RadioButton("spp", &axis, 1);
    convergence.againstSpp = axis == 1;
    ImGui::SameLine();
    ImGui::Checkbox("MC slope", &convergence.slope);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("the Monte Carlo rate through the newest run's first point:\n"
                        "relMSE ~ 1/t; RMSE and MAPE ~ 1/sqrt(t)");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("keep 16").x + 16.f * uiScale);
    ImGui::DragInt("##keep", &convergence.maxSeries, 0.1f, 1, 16, "keep %d", ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("runs kept in the plot (drag); the oldest go first");
    ImGui::SameLine();
    if (ImGui::SmallButton("clear")) reference.errors->clear();
    ImGui::SameLine();
    if (ImGui::SmallButton("CSV")) requests.exportErrorCsv = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("save every point as out/pathlab-error-<time>.csv");
  };
  auto plot = [&] {
    const ErrorTracker& errors = *reference.errors;
    if (!errors.reference() && convergence.series.empty()) {
      ImGui::TextWrapped("No reference: load one in the side panel (Reference and error) or take the current "
                         "image (Ctrl+R); every configuration after that is one line here, kept when you change it.");
      return;
    }
    if (!reference.status.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.7f, 0.2f, 1.f));
      ImGui::TextUnformatted(("not measuring: " + reference.status).c_str());
      ImGui::PopStyleColor();
    } else if (const std::shared_ptr<const Image> image = errors.reference();
               image && ImGui::GetContentRegionAvail().y > 160.f * uiScale) {
      ImGui::TextDisabled("against %s (%d x %d)", errors.referenceSource().c_str(), image->width, image->height);
    }
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    drawErrorPlot(convergence.series,
                  ErrorPlotOptions{convergence.metric, convergence.againstSpp, convergence.slope, uiScale}, avail);
  };
  if (sideBySide) {
    const float plotWidth = 0.5f * ImGui::GetContentRegionAvail().x;
    ImGui::BeginChild("plot", ImVec2(plotWidth, 0.f), false, ImGuiWindowFlags_NoScrollbar);
    plotControls();
    plot();
    ImGui::EndChild();
    ImGui::SameLine();
    ImGui::BeginChild("table", ImVec2(0.f, 0.f), false);
    drawTechniqueTable(snapshot);
    ImGui::EndChild();
  } else if (ImGui::BeginTabBar("convergence")) {
    if (ImGui::BeginTabItem("Error plot")) {
      plotControls();
      plot();
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Techniques: rays and time")) {
      drawTechniqueTable(snapshot);
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

void drawTechniqueTable(const RenderSnapshot& s) {
  const Counters& c = s.counters;
  if (s.settings.integrator == IntegratorKind::Pt) {
    ImGui::TextWrapped("The path tracer has no (s,t) techniques to compare: %s rays/s (%s closest-hit, %s shadow rays)",
                       compactCount(static_cast<double>(c.totalRays()) / std::max(s.renderSeconds, 1e-9)).c_str(),
                       compactCount(static_cast<double>(c.rays)).c_str(), compactCount(static_cast<double>(c.shadowRays)).c_str());
    return;
  }
  std::vector<TechniqueRow> rows = techniqueRows(c, s.settings.maxLength, s.renderSeconds);
  ImGui::Text("%s rays in %.1f s: %s rays/s", compactCount(static_cast<double>(c.totalRays())).c_str(), s.renderSeconds,
              compactCount(static_cast<double>(c.totalRays()) / std::max(s.renderSeconds, 1e-9)).c_str());
  ImGui::SameLine();
  const bool timed = c.timedSamples > 0;
  if (timed)
    ImGui::TextDisabled("time: from %.0f%% of the samples", 100.0 * static_cast<double>(c.timedSamples) /
                                                              static_cast<double>(std::max<uint64_t>(c.cameraSamples, 1)));
  else
    ImGui::TextDisabled("time: not yet timed");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("connect() + MIS weight per technique, the walks per subpath, summed over threads;\n"
                      "timed on one camera sample in eight, picked at random, only while this panel is open");
  const std::span<const TechniqueColumnInfo> columns = techniqueColumns();
  const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit |
                                ImGuiTableFlags_Resizable;
  if (!ImGui::BeginTable("techniques", static_cast<int>(columns.size()), flags)) return;
  ImGui::TableSetupScrollFreeze(1, 1);
  for (const TechniqueColumnInfo& col : columns)
    ImGui::TableSetupColumn(col.header, col.column == TechniqueColumn::Name ? ImGuiTableColumnFlags_DefaultSort
                                                                             : ImGuiTableColumnFlags_PreferSortDescending,
                            0.f, static_cast<ImGuiID>(col.column));
  ImGui::TableNextRow(ImGuiTableRowFlags_Headers);
  for (size_t i = 0; i < columns.size(); ++i) {
    ImGui::TableSetColumnIndex(static_cast<int>(i));
    ImGui::TableHeader(columns[i].header);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", columns[i].help);
  }
  if (ImGuiTableSortSpecs* sort = ImGui::TableGetSortSpecs(); sort && sort->SpecsCount > 0)
    sortRows(rows, static_cast<TechniqueColumn>(sort->Specs[0].ColumnUserID),
             sort->Specs[0].SortDirection == ImGuiSortDirection_Descending);
  for (const TechniqueRow& r : rows) {
    ImGui::TableNextRow();
    // Greyed: the techniques an isolated image does not show.
    const bool shown = r.s < 0 || !s.settings.isolate || (s.settings.isolate->s == r.s && s.settings.isolate->t == r.t);
    if (!shown) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    for (size_t i = 0; i < columns.size(); ++i) {
      ImGui::TableSetColumnIndex(static_cast<int>(i));
      ImGui::TextUnformatted(techniqueCell(r, columns[i].column, timed).c_str());
      if (i == 0 && r.walk && ImGui::IsItemHovered())
        ImGui::SetTooltip("%s: closest-hit rays of the random walks (tried: subpaths)", r.name.c_str());
    }
    if (!shown) ImGui::PopStyleColor();
  }
  ImGui::EndTable();
}

}  // namespace pathlab::ui
