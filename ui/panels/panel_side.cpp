// The side panel's status, display, scene and presets sections.
#include "ui/panels/panels.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

std::string humanCount(double v) {
  if (v >= 1e9) return fmt::format("{:.2f} G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f} M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f} k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

}  // namespace

void drawStatusSection(const RenderSnapshot& s, const std::string& warning, RunState& run, double frameMs,
                       PanelRequests& requests) {
  const Counters& c = s.counters;
  const double seconds = std::max(s.seconds, 1e-9);
  if (ImGui::Button(run.userPaused ? "Resume (Space)" : "Pause (Space)")) requests.actions.push_back(Action::TogglePause);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
  int target = static_cast<int>(run.targetSpp);
  if (ImGui::InputInt("stop at spp", &target, 0, 0)) run.targetSpp = static_cast<uint64_t>(std::max(target, 0));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("0: never stop");
  if (s.preview) ImGui::Text("preview 1/%d   %.2f s", s.previewFactor, s.seconds);
  else ImGui::Text("%llu spp   %.1f s%s", static_cast<unsigned long long>(s.samplesPerPixel), s.seconds,
                   run.userPaused ? "   (paused)" : run.targetSpp > 0 && s.samplesPerPixel >= run.targetSpp ? "   (done)" : "");
  ImGui::Text("%s samples/s   %s rays/s", humanCount(static_cast<double>(c.cameraSamples) / seconds).c_str(),
              humanCount(static_cast<double>(c.totalRays()) / seconds).c_str());
  if (c.discarded() > 0) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.7f, 0.2f, 1.f));
  const DiscardCounts d = c.discardedCounts();
  ImGui::Text("discarded %llu (NaN %llu, Inf %llu, negative %llu)", static_cast<unsigned long long>(d.total()),
              static_cast<unsigned long long>(d.nan), static_cast<unsigned long long>(d.inf),
              static_cast<unsigned long long>(d.negative));
  if (c.discarded() > 0) ImGui::PopStyleColor();
  ImGui::TextWrapped("%d x %d, generation %llu: %s", s.settings.width, s.settings.height,
                     static_cast<unsigned long long>(s.generation), describe(s.settings).c_str());
  if (!warning.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.f, 0.7f, 0.2f, 1.f));
    ImGui::TextWrapped("%s", warning.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::TextDisabled("UI %.1f ms/frame", frameMs);
}

void drawDisplaySection(DisplaySettings& display, RunState& run, PyramidView& pyramid, const Image& shown) {
  ImGui::PushID("display");
  ImGui::SliderFloat("exposure", &display.exposure, -10.f, 10.f, "%+.1f stops");
  ImGui::SameLine();
  if (ImGui::SmallButton("auto") && shown.width > 0) display.exposure = autoExposure(shown);
  int toneMap = static_cast<int>(display.toneMap);
  ImGui::RadioButton("clamp", &toneMap, static_cast<int>(ToneMap::Clamp));
  ImGui::SameLine();
  ImGui::RadioButton("filmic (ACES)", &toneMap, static_cast<int>(ToneMap::Filmic));
  display.toneMap = static_cast<ToneMap>(toneMap);
  ImGui::SameLine();
  ImGui::Checkbox("false colour", &display.falseColour);
  if (display.falseColour) {
    ImGui::DragFloatRange2("log10 range", &display.logMin, &display.logMax, 0.05f, -12.f, 12.f, "%.1f", "%.1f");
    display.logMax = std::max(display.logMax, display.logMin + 0.1f);
    // Colour bar: one segment per tenth of the range.
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImVec2 p = ImGui::GetCursorScreenPos();
    const float w = ImGui::GetContentRegionAvail().x, h = ImGui::GetTextLineHeight();
    for (int i = 0; i < 20; ++i) {
      const Vec3 a = turbo(static_cast<float>(i) / 20.f), b = turbo(static_cast<float>(i + 1) / 20.f);
      const ImU32 ca = ImGui::ColorConvertFloat4ToU32(ImVec4(a.r, a.g, a.b, 1.f));
      const ImU32 cb = ImGui::ColorConvertFloat4ToU32(ImVec4(b.r, b.g, b.b, 1.f));
      draw->AddRectFilledMultiColor(ImVec2(p.x + w * static_cast<float>(i) / 20.f, p.y),
                                    ImVec2(p.x + w * static_cast<float>(i + 1) / 20.f, p.y + h), ca, cb, cb, ca);
    }
    ImGui::Dummy(ImVec2(w, h));
    ImGui::Text("1e%.1f", display.logMin);
    ImGui::SameLine(w - ImGui::CalcTextSize("1e+0.0").x);
    ImGui::Text("1e%.1f", display.logMax);
  }
  static const float scales[] = {1.f, 0.5f, 0.25f};
  int scale = run.resolutionScale == 1.f ? 0 : run.resolutionScale == 0.5f ? 1 : 2;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.4f);
  if (ImGui::Combo("resolution", &scale, "100%\00050%\00025%\0")) run.resolutionScale = scales[scale];
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("render resolution relative to the window (restarts)");
  ImGui::Checkbox("technique pyramid (G)", &pyramid.show);
  if (pyramid.show) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x);
    ImGui::SliderInt("##pyramidLength", &pyramid.length, 1, 6, "up to length %d");
  }
  ImGui::PopID();
}

void drawSceneSection(SceneState& scene, bool cameraMoved, PanelRequests& requests) {
  ImGui::PushID("scene");
  ImGui::TextWrapped("%s", scene.path.c_str());
  if (scene.loader.busy()) ImGui::TextDisabled("loading %s ...", scene.loader.pendingPath().c_str());
  if (ImGui::Button("Reload (F5)")) requests.actions.push_back(Action::ReloadScene);
  ImGui::SameLine();
  if (ImGui::Button("Rescan")) requests.rescanScenes = true;
  ImGui::TextDisabled("open one, or drop a .gltf / .glb on the window:");
  for (const std::string& file : scene.files)
    if (ImGui::Selectable(file.c_str(), file == scene.path)) requests.openScene = file;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.7f);
  if (ImGui::InputText("open", &scene.typedPath, ImGuiInputTextFlags_EnterReturnsTrue) && !scene.typedPath.empty())
    requests.openScene = scene.typedPath;
  ImGui::Separator();
  if (ImGui::Button("Reset camera (R)")) requests.actions.push_back(Action::ResetCamera);
  ImGui::SameLine();
  ImGui::TextDisabled(cameraMoved ? "moved" : "scene camera");
  const Vec3 eye = scene.orbit.eye(), pivot = scene.orbit.pivot();
  ImGui::TextDisabled("eye %.2f %.2f %.2f  pivot %.2f %.2f %.2f", eye.x, eye.y, eye.z, pivot.x, pivot.y, pivot.z);
  ImGui::Separator();
  if (ImGui::Button("Save image (Ctrl+S)")) requests.actions.push_back(Action::SaveImage);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("out/pathlab-<time>.exr (linear) and .png (exposure, clamp, sRGB)");
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F12)")) requests.actions.push_back(Action::Screenshot);
  ImGui::PopID();
}

void drawPresetSection(const PresetState& presets, PanelRequests& requests) {
  ImGui::PushID("presets");
  if (presets.presets.empty()) {
    ImGui::TextDisabled("none loaded: pathlab view --presets FILE (e.g. assets/presets.json)");
  } else {
    ImGui::TextDisabled("%s (PageUp / PageDown)", presets.path.c_str());
    for (size_t i = 0; i < presets.presets.size(); ++i)
      if (ImGui::Selectable(presets.presets[i].name.c_str(), static_cast<int>(i) == presets.current))
        requests.preset = static_cast<int>(i);
  }
  ImGui::PopID();
}

}  // namespace pathlab::ui
