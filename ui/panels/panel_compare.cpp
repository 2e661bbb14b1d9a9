// The side panel's comparison section: side by side on / off, side B's CONFIG (the syntax of
// `pathlab converge --configs`), swap. Side A is what the rest of the panel edits.
#include "ui/panels/panels.h"

#include <fmt/core.h>

#include <array>
#include <cstring>

namespace pathlab::ui {

void drawCompareSection(CompareState& compare, const RenderSnapshot& b, const std::string& refused,
                        PanelRequests& requests) {
  ImGui::PushID("compare");
  bool on = compare.on;
  if (ImGui::Checkbox("Side by side (C)", &on)) requests.actions.push_back(Action::ToggleCompare);
  ImGui::SameLine();
  if (ImGui::Button("Swap A | B (V)")) requests.actions.push_back(Action::SwapCompareSides);
  ImGui::TextWrapped("A: the estimator below, edited by every control and key. B: a configuration as in converge, "
                     "e.g. pt, bpt:mis=power, bpt:techniques=t=1. Equal threads each; the camera is shared.");
  std::array<char, 256> buffer{};
  std::strncpy(buffer.data(), compare.typed.c_str(), buffer.size() - 1);
  ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Apply").x - 3.f * ImGui::GetStyle().FramePadding.x);
  const bool entered = ImGui::InputText("##config", buffer.data(), buffer.size(), ImGuiInputTextFlags_EnterReturnsTrue);
  compare.typed = buffer.data();
  ImGui::SameLine();
  if (ImGui::Button("Apply") || entered) requests.compareConfig = compare.typed;
  for (const std::string* error : {static_cast<const std::string*>(&compare.error), &refused}) {
    if (error->empty()) continue;
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.35f, 0.35f, 1.f));
    ImGui::TextWrapped("%s", error->c_str());
    ImGui::PopStyleColor();
  }
  if (compare.on && b.settings.width > 0)
    ImGui::TextWrapped("B: %s, %llu spp in %.1f s", describe(b.settings).c_str(),
                       static_cast<unsigned long long>(b.samplesPerPixel), b.renderSeconds);
  ImGui::PopID();
}

}  // namespace pathlab::ui
