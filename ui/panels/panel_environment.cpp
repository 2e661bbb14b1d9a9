// The side panel's Environment section: what lights the scene besides its own lights.
#include "ui/panels/panels.h"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace pathlab::ui {

void drawEnvironmentSection(EnvironmentState& env) {
  ImGui::PushID("environment");
  EnvironmentChoice& edited = env.edited;
  ImGui::TextWrapped("lit by: %s", describe(env.applied).c_str());
  if (!(edited == env.applied)) ImGui::TextDisabled("relighting ...");
  const float fieldWidth = ImGui::GetContentRegionAvail().x * 0.62f;
  ImGui::SetNextItemWidth(fieldWidth);
  const bool entered = ImGui::InputTextWithHint("##map", "FILE.exr or FILE.hdr", &env.typedPath,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Load map") || entered) && !env.typedPath.empty()) edited.spec = env.typedPath;
  ImGui::TextDisabled("a lat-long map; or drop an .exr / .hdr on the window");
  ImGui::SetNextItemWidth(fieldWidth);
  const bool colourChanged =
      ImGui::ColorEdit3("##colour", &env.colour.x, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR);
  // While a colour lights the scene, editing it relights at once; otherwise the button switches.
  const bool colourShown = !edited.spec.empty() && !isEnvironmentFile(edited.spec);
  ImGui::SameLine();
  if (ImGui::Button("Uniform") || (colourChanged && colourShown)) edited.spec = colourSpec(env.colour);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a constant radiance from every direction");
  if (ImGui::Button("None")) edited.spec.clear();
  ImGui::SameLine();
  ImGui::TextDisabled("the file's own lights only");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a file without any gets the default light (uniform white)");
  ImGui::BeginDisabled(edited.spec.empty());
  ImGui::SliderFloat("strength", &edited.strength, 0.f, 100.f, "%.3g", ImGuiSliderFlags_Logarithmic);
  edited.strength = std::max(edited.strength, 0.f);
  ImGui::SliderFloat("rotation", &edited.rotationDegrees, -180.f, 180.f, "%.0f deg");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("about the vertical (+y) axis; Ctrl+click to type a value");
  ImGui::EndDisabled();
  // Next-event estimation's light choice (--light-sampler): a relight like the others.
  const char* names[] = {"auto", "power", "bvh"};
  int selection = static_cast<int>(edited.lightSelection);
  ImGui::SetNextItemWidth(fieldWidth * 0.6f);
  if (ImGui::Combo("next-event lights", &selection, names, 3)) edited.lightSelection = static_cast<LightSelection>(selection);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("how next-event estimation (s = 1) chooses a light: bvh by what each can send to the receiving "
                      "point, power in proportion to power, auto: bvh when the scene has more than one emitter. "
                      "Light subpaths always start by power");
  ImGui::PopID();
}

}  // namespace pathlab::ui
