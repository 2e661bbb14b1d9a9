// The outliers section of the side panel (the list of the brightest contributions, a click opens
// one) and their marks over the image.
#include "core/sampling/technique_label.h"
#include "ui/panels/panels.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::ui {

void drawOutlierSection(OutlierListState& state, const RenderSettings& edited, const RenderSnapshot& shown,
                        PanelRequests& requests) {
  ImGui::PushID("outliers");
  ImGui::Checkbox("Find the brightest contributions", &state.on);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Keeps the weighted (s,t) contributions of highest luminance of the image's passes, the "
                      "fireflies, as `pathlab outliers` lists them. Every sample then takes the kernel's recording "
                      "route: rendering is slower while this is on.");
  if (!state.on) {
    ImGui::PopID();
    return;
  }
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 4.f);
  if (ImGui::InputInt("kept", &state.count, 0)) state.count = std::clamp(state.count, 1, kMaxViewerOutliers);
  ImGui::Checkbox("mark them on the image", &state.markers);
  if (const std::string problem = outlierFinderProblem(edited); !problem.empty()) {
    ImGui::TextWrapped("%s", problem.c_str());
    ImGui::PopID();
    return;
  }
  const OutlierList& list = state.list;
  if (state.rows.empty()) {
    // The finder starts between passes: none come while paused or at the sample target.
    ImGui::TextDisabled("the list comes with the next full pass (none while paused or at 'stop at spp')");
    ImGui::PopID();
    return;
  }
  const std::string of = list.generation == shown.generation
                             ? std::string()
                             : fmt::format(" of an earlier image ({} x {}, generation {})", list.settings.width,
                                           list.settings.height, list.generation);
  ImGui::TextWrapped("the %zu brightest of passes %llu-%llu%s; click one: its sample in the path inspector and the 3D "
                     "view",
                     state.rows.size(), static_cast<unsigned long long>(list.firstPass),
                     static_cast<unsigned long long>(list.passes - 1), of.c_str());
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_ScrollY |
                                ImGuiTableFlags_SizingFixedFit;
  const float rowHeight = ImGui::GetTextLineHeightWithSpacing();
  const float height = rowHeight * (static_cast<float>(std::min<size_t>(state.rows.size(), 10)) + 1.5f);
  if (ImGui::BeginTable("list", 6, flags, ImVec2(0.f, height))) {
    ImGui::TableSetupScrollFreeze(0, 1);
    ImGui::TableSetupColumn("#");
    ImGui::TableSetupColumn("luminance");
    ImGui::TableSetupColumn("pixel");
    ImGui::TableSetupColumn("sample");
    ImGui::TableSetupColumn("(s,t)");
    ImGui::TableSetupColumn("p / best");
    ImGui::TableHeadersRow();
    for (size_t i = 0; i < state.rows.size(); ++i) {
      const OutlierRow& row = state.rows[i];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const std::string rank = fmt::format("{}", i + 1);
      if (ImGui::Selectable(rank.c_str(), state.opened == static_cast<int>(i), ImGuiSelectableFlags_SpanAllColumns))
        requests.openOutlier = static_cast<int>(i);
      if (ImGui::IsItemHovered()) {
        std::string tip = fmt::format("{} lands at {:.1f}, {:.1f}", techniqueLabel(row.o.technique), row.o.pRaster.x,
                                      row.o.pRaster.y);
        if (row.replayed && row.densityRatio > 0.0)
          tip += fmt::format("\nits technique's density is {:.3g} of {}'s, the largest enabled one", row.densityRatio,
                             techniqueLabel(row.best));
        if (const std::string why = outlierRatioProblem(list, row.o); !why.empty()) tip += "\np / best: " + why;
        ImGui::SetTooltip("%s", tip.c_str());
      }
      ImGui::TableNextColumn();
      ImGui::Text("%.4g", static_cast<double>(row.o.luminance));
      ImGui::TableNextColumn();
      ImGui::Text("%d,%d", row.o.id.x, row.o.id.y);
      ImGui::TableNextColumn();
      ImGui::Text("%llu", static_cast<unsigned long long>(row.o.id.sample));
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(techniqueLabel(row.o.technique).c_str());
      ImGui::TableNextColumn();
      if (row.replayed && row.densityRatio > 0.0) ImGui::Text("%.3g", row.densityRatio);
      else ImGui::TextDisabled("-");
    }
    ImGui::EndTable();
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("p / best: the density of the technique that sampled the path over the largest among the "
                     "enabled techniques able to sample it (1: no enabled technique samples it better)");
  ImGui::PopStyleColor();
  ImGui::PopID();
}

void drawOutlierMarkers(const OutlierListState& state, ImVec2 origin, ImVec2 size, const RenderSettings& shown,
                        float uiScale) {
  // The list's image must show what is shown, at whatever size (its positions scale with it).
  const Vec2i raster(state.list.settings.width, state.list.settings.height);
  if (!state.on || !state.markers || state.rows.empty() || raster.x <= 0 || raster.y <= 0 ||
      !sameExceptSize(state.list.settings, shown))
    return;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  draw->PushClipRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), true);
  const float sx = size.x / static_cast<float>(raster.x), sy = size.y / static_cast<float>(raster.y);
  const float r = 6.f * uiScale;
  for (size_t i = 0; i < state.rows.size(); ++i) {
    const Vec2 p = state.rows[i].o.pRaster;
    const ImVec2 c(origin.x + p.x * sx, origin.y + p.y * sy);
    // Magenta rings, the opened one thicker: where each firefly landed, whatever its technique.
    const bool opened = state.opened == static_cast<int>(i);
    draw->AddCircle(c, r + 1.f * uiScale, IM_COL32(0, 0, 0, 200), 0, (opened ? 4.f : 3.f) * uiScale);
    draw->AddCircle(c, r, IM_COL32(255, 60, 220, 255), 0, (opened ? 2.5f : 1.5f) * uiScale);
    if (i < 9) {
      const std::string label = fmt::format("{}", i + 1);
      draw->AddText(ImVec2(c.x + r + 2.f * uiScale, c.y - r - 2.f * uiScale), IM_COL32(255, 60, 220, 255), label.c_str());
    }
  }
  draw->PopClipRect();
}

}  // namespace pathlab::ui
