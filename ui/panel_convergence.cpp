// The convergence panel along the bottom: the live error plot of every kept run (error against
// render time or samples per pixel) and the per-technique table of rays and time.
#include "ui/viewer.h"

#include "ui/error_plot.h"
#include "ui/technique_table.h"

#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

std::string compact(double v) {
  if (v >= 1e9) return fmt::format("{:.2f}G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f}M", v / 1e6);
  if (v >= 1e4) return fmt::format("{:.1f}k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

}  // namespace

float Viewer::convergencePanelHeight(float windowHeight) const {
  // A third of the window, but room for a readable plot in small windows (640 x 480).
  return std::clamp(0.36f * windowHeight, std::min(200.f * uiScale_, 0.45f * windowHeight), 360.f * uiScale_);
}

void Viewer::drawConvergenceWindow(float y, float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(0.f, y));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus |
                                 ImGuiWindowFlags_NoScrollbar;
  if (!ImGui::Begin("Convergence (P)", &showConvergence_, flags)) {
    ImGui::End();
    return;
  }
  const bool sideBySide = width >= 820.f * uiScale_;
  auto plotControls = [&] {
    int metric = static_cast<int>(plotMetric_);
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("relMSE").x + ImGui::GetFrameHeight() + 12.f * uiScale_);
    if (ImGui::Combo("##metric", &metric, "relMSE\0RMSE\0MAPE\0")) plotMetric_ = static_cast<ErrorMetric>(metric);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("relMSE: mean (x - r)^2 / (r^2 + 0.01)\nRMSE: sqrt(mean (x - r)^2)\nMAPE: mean |x - r| / (|r| + 0.01)");
    ImGui::SameLine();
    int axis = plotAgainstSpp_ ? 1 : 0;
    ImGui::RadioButton("time", &axis, 0);
    ImGui::SameLine();
    ImGui::RadioButton("spp", &axis, 1);
    plotAgainstSpp_ = axis == 1;
    ImGui::SameLine();
    ImGui::Checkbox("MC slope", &plotSlope_);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("the Monte Carlo rate through the newest run's first point:\n"
                        "relMSE ~ 1/t; RMSE and MAPE ~ 1/sqrt(t)");
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::CalcTextSize("keep 16").x + 16.f * uiScale_);
    ImGui::DragInt("##keep", &maxSeries_, 0.1f, 1, 16, "keep %d", ImGuiSliderFlags_AlwaysClamp);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("runs kept in the plot (drag); the oldest go first");
    ImGui::SameLine();
    if (ImGui::SmallButton("clear")) errors_->clear();
    ImGui::SameLine();
    if (ImGui::SmallButton("CSV")) exportErrorCsv();
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("save every point as out/pathlab-error-<time>.csv");
  };
  auto plot = [&] {
    if (!errors_->reference() && series_.empty()) {
      ImGui::TextWrapped("No reference: load one in the side panel (Reference and error) or take the current "
                         "image (Ctrl+R); every configuration after that is one line here, kept when you change it.");
      return;
    }
    if (!referenceStatus_.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.7f, 0.2f, 1.f));
      ImGui::TextUnformatted(("not measuring: " + referenceStatus_).c_str());
      ImGui::PopStyleColor();
    } else if (const std::shared_ptr<const Image> reference = errors_->reference();
               reference && ImGui::GetContentRegionAvail().y > 160.f * uiScale_) {
      ImGui::TextDisabled("against %s (%d x %d)", errors_->referenceSource().c_str(), reference->width, reference->height);
    }
    const ImVec2 avail = ImGui::GetContentRegionAvail();
    drawErrorPlot(series_, ErrorPlotOptions{plotMetric_, plotAgainstSpp_, plotSlope_, uiScale_}, avail);
  };
  if (sideBySide) {
    const float plotWidth = 0.5f * ImGui::GetContentRegionAvail().x;
    ImGui::BeginChild("plot", ImVec2(plotWidth, 0.f), false, ImGuiWindowFlags_NoScrollbar);
    plotControls();
    plot();
    ImGui::EndChild();
    ImGui::SameLine();
    ImGui::BeginChild("table", ImVec2(0.f, 0.f), false);
    drawTechniqueTable();
    ImGui::EndChild();
  } else if (ImGui::BeginTabBar("convergence")) {
    if (ImGui::BeginTabItem("Error plot")) {
      plotControls();
      plot();
      ImGui::EndTabItem();
    }
    if (ImGui::BeginTabItem("Techniques: rays and time")) {
      drawTechniqueTable();
      ImGui::EndTabItem();
    }
    ImGui::EndTabBar();
  }
  ImGui::End();
}

void Viewer::drawTechniqueTable() {
  const RenderSnapshot& s = snapshot_;
  const Counters& c = s.counters;
  if (s.settings.integrator == IntegratorKind::Pt) {
    ImGui::TextWrapped("The path tracer has no (s,t) techniques to compare: %s rays/s (%s closest-hit, %s shadow rays)",
                       compact(static_cast<double>(c.totalRays()) / std::max(s.renderSeconds, 1e-9)).c_str(),
                       compact(static_cast<double>(c.rays)).c_str(), compact(static_cast<double>(c.shadowRays)).c_str());
    return;
  }
  std::vector<TechniqueRow> rows = techniqueRows(c, s.settings.maxLength, s.renderSeconds);
  ImGui::Text("%s rays in %.1f s: %s rays/s", compact(static_cast<double>(c.totalRays())).c_str(), s.renderSeconds,
              compact(static_cast<double>(c.totalRays()) / std::max(s.renderSeconds, 1e-9)).c_str());
  ImGui::SameLine();
  if (c.timedSamples > 0)
    ImGui::TextDisabled("time: from %.0f%% of the samples", 100.0 * static_cast<double>(c.timedSamples) /
                                                              static_cast<double>(std::max<uint64_t>(c.cameraSamples, 1)));
  else
    ImGui::TextDisabled("time: not yet timed");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("connect() + MIS weight per technique, the walks per subpath, summed over threads;\n"
                      "timed on one camera sample in eight, picked at random, only while this panel is open");
  constexpr int kColumns = 9;
  const ImGuiTableFlags flags = ImGuiTableFlags_Sortable | ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV |
                                ImGuiTableFlags_ScrollY | ImGuiTableFlags_ScrollX | ImGuiTableFlags_SizingFixedFit |
                                ImGuiTableFlags_Resizable;
  if (!ImGui::BeginTable("techniques", kColumns, flags)) return;
  ImGui::TableSetupScrollFreeze(1, 1);
  ImGui::TableSetupColumn("(s,t)", ImGuiTableColumnFlags_DefaultSort, 0.f, static_cast<ImGuiID>(TechniqueColumn::Name));
  ImGui::TableSetupColumn("tried", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::Tried));
  ImGui::TableSetupColumn("rays", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::Rays));
  ImGui::TableSetupColumn("rays/s", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::RaysPerSecond));
  ImGui::TableSetupColumn("% rays", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::RayShare));
  ImGui::TableSetupColumn("% time", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::TimeShare));
  ImGui::TableSetupColumn("ns/try", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::TimePerTry));
  ImGui::TableSetupColumn("contrib.", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::Contributed));
  ImGui::TableSetupColumn("blocked", ImGuiTableColumnFlags_PreferSortDescending, 0.f, static_cast<ImGuiID>(TechniqueColumn::Blocked));
  ImGui::TableHeadersRow();
  if (ImGuiTableSortSpecs* sort = ImGui::TableGetSortSpecs(); sort && sort->SpecsCount > 0)
    sortRows(rows, static_cast<TechniqueColumn>(sort->Specs[0].ColumnUserID),
             sort->Specs[0].SortDirection == ImGuiSortDirection_Descending);
  for (const TechniqueRow& r : rows) {
    ImGui::TableNextRow();
    const bool walk = r.s < 0 && r.name != fmt::format("k>{}", kCountedLength);
    const bool enabled = walk || r.s < 0 || (s.settings.isolate ? s.settings.isolate->s == r.s && s.settings.isolate->t == r.t
                                                                : true);
    if (!enabled) ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    auto cell = [&](int column, const std::string& text) {
      ImGui::TableSetColumnIndex(column);
      ImGui::TextUnformatted(text.c_str());
    };
    cell(0, r.name);
    if (ImGui::IsItemHovered() && walk)
      ImGui::SetTooltip("%s: closest-hit rays of the random walks (tried: subpaths)", r.name.c_str());
    cell(1, compact(static_cast<double>(r.tried)));
    cell(2, compact(static_cast<double>(r.rays)));
    cell(3, compact(r.raysPerSecond));
    cell(4, fmt::format("{:.1f}", 100.0 * r.rayShare));
    cell(5, c.timedSamples > 0 ? fmt::format("{:.1f}", 100.0 * r.timeShare) : std::string("-"));
    cell(6, c.timedSamples > 0 ? fmt::format("{:.0f}", r.nanosecondsPerTry) : std::string("-"));
    cell(7, walk ? std::string() : compact(static_cast<double>(r.contributed)));
    cell(8, walk ? std::string() : r.tried > 0 ? fmt::format("{:.0f}%", 100.0 * static_cast<double>(r.blocked) / static_cast<double>(r.tried)) : "-");
    if (!enabled) ImGui::PopStyleColor();
  }
  ImGui::EndTable();
}

}  // namespace pathlab::ui
