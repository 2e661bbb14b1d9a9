// The side panel: status, estimator (panel_techniques.cpp), display, scene and presets sections.
#include "ui/viewer.h"

#include "ui/technique_grid.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <cmath>
#include <filesystem>

namespace pathlab::ui {

namespace {

std::string humanCount(double v) {
  if (v >= 1e9) return fmt::format("{:.2f} G", v / 1e9);
  if (v >= 1e6) return fmt::format("{:.2f} M", v / 1e6);
  if (v >= 1e3) return fmt::format("{:.1f} k", v / 1e3);
  return fmt::format("{:.0f}", v);
}

constexpr double kMessageSeconds = 12.0;

}  // namespace

void Viewer::drawSidePanel(float width, float height) {
  ImGui::SetNextWindowPos(ImVec2(0.f, 0.f));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::Begin("pathlab", nullptr, flags);
  const std::string title = "pathlab  " + std::filesystem::path(scenePath_).filename().string();
  ImGui::TextUnformatted(title.c_str());
  const float helpWidth = ImGui::CalcTextSize("Help (F1)").x + 2.f * ImGui::GetStyle().FramePadding.x;
  const float right = ImGui::GetWindowContentRegionMax().x - helpWidth;
  if (ImGui::GetItemRectSize().x + ImGui::GetStyle().ItemSpacing.x < right - ImGui::GetStyle().WindowPadding.x)
    ImGui::SameLine(right);
  if (ImGui::SmallButton("Help (F1)")) showHelp_ = !showHelp_;
  const double age = std::chrono::duration<double>(std::chrono::steady_clock::now() - messageTime_).count();
  if (!message_.empty() && (messageIsError_ || age < kMessageSeconds)) {
    ImGui::PushStyleColor(ImGuiCol_Text, messageIsError_ ? ImVec4(1.f, 0.35f, 0.35f, 1.f) : ImVec4(0.6f, 0.9f, 0.6f, 1.f));
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
    if (messageIsError_ && ImGui::SmallButton("dismiss")) message_.clear();
  }
  if (ImGui::CollapsingHeader("Status", ImGuiTreeNodeFlags_DefaultOpen)) drawStatusSection();
  if (ImGui::CollapsingHeader("Estimator", ImGuiTreeNodeFlags_DefaultOpen)) drawEstimatorSection();
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen)) drawDisplaySection();
  if (ImGui::CollapsingHeader("Reference and error", showConvergence_ ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawReferenceSection();
  if (ImGui::CollapsingHeader("Scene and camera")) drawSceneSection();
  if (ImGui::CollapsingHeader("Presets", presets_.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen)) drawPresetSection();
  ImGui::End();
}

void Viewer::drawStatusSection() {
  const RenderSnapshot& s = snapshot_;
  const Counters& c = s.counters;
  const double seconds = std::max(s.seconds, 1e-9);
  if (ImGui::Button(userPaused_ ? "Resume (Space)" : "Pause (Space)")) perform(Action::TogglePause);
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
  int target = static_cast<int>(targetSpp_);
  if (ImGui::InputInt("stop at spp", &target, 0, 0)) {
    targetSpp_ = static_cast<uint64_t>(std::max(target, 0));
    renderer_->setTargetSpp(targetSpp_);
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("0: never stop");
  if (s.preview) ImGui::Text("preview 1/%d   %.2f s", s.previewFactor, s.seconds);
  else ImGui::Text("%llu spp   %.1f s%s", static_cast<unsigned long long>(s.samplesPerPixel), s.seconds,
                   userPaused_ ? "   (paused)" : targetSpp_ > 0 && s.samplesPerPixel >= targetSpp_ ? "   (done)" : "");
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
  ImGui::TextDisabled("UI %.1f ms/frame", frameMs_);
}

void Viewer::drawDisplaySection() {
  ImGui::PushID("display");
  ImGui::SliderFloat("exposure", &display_.exposure, -10.f, 10.f, "%+.1f stops");
  ImGui::SameLine();
  if (ImGui::SmallButton("auto") && snapshot_.image.width > 0) display_.exposure = autoExposure(snapshot_.image);
  int toneMap = static_cast<int>(display_.toneMap);
  ImGui::RadioButton("clamp", &toneMap, static_cast<int>(ToneMap::Clamp));
  ImGui::SameLine();
  ImGui::RadioButton("filmic (ACES)", &toneMap, static_cast<int>(ToneMap::Filmic));
  display_.toneMap = static_cast<ToneMap>(toneMap);
  ImGui::SameLine();
  ImGui::Checkbox("false colour", &display_.falseColour);
  if (display_.falseColour) {
    ImGui::DragFloatRange2("log10 range", &display_.logMin, &display_.logMax, 0.05f, -12.f, 12.f, "%.1f", "%.1f");
    display_.logMax = std::max(display_.logMax, display_.logMin + 0.1f);
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
    ImGui::Text("1e%.1f", display_.logMin);
    ImGui::SameLine(w - ImGui::CalcTextSize("1e+0.0").x);
    ImGui::Text("1e%.1f", display_.logMax);
  }
  static const float scales[] = {1.f, 0.5f, 0.25f};
  int scale = resolutionScale_ == 1.f ? 0 : resolutionScale_ == 0.5f ? 1 : 2;
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.4f);
  if (ImGui::Combo("resolution", &scale, "100%\00050%\00025%\0")) resolutionScale_ = scales[scale];
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("render resolution relative to the window (restarts)");
  ImGui::Checkbox("technique pyramid (G)", &showPyramid_);
  if (showPyramid_) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x);
    ImGui::SliderInt("##pyramidLength", &pyramidLength_, 1, 6, "up to length %d");
  }
  ImGui::PopID();
}

void Viewer::drawSceneSection() {
  ImGui::PushID("scene");
  ImGui::TextWrapped("%s", scenePath_.c_str());
  if (loader_.busy()) ImGui::TextDisabled("loading %s ...", loader_.pendingPath().c_str());
  if (ImGui::Button("Reload (F5)")) openScene(scenePath_);
  ImGui::SameLine();
  if (ImGui::Button("Rescan")) refreshSceneFiles();
  ImGui::TextDisabled("open one, or drop a .gltf / .glb on the window:");
  for (const std::string& file : sceneFiles_)
    if (ImGui::Selectable(file.c_str(), file == scenePath_)) openScene(file);
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.7f);
  if (ImGui::InputText("open", &typedScenePath_, ImGuiInputTextFlags_EnterReturnsTrue) && !typedScenePath_.empty())
    openScene(typedScenePath_);
  ImGui::Separator();
  if (ImGui::Button("Reset camera (R)")) resetCamera();
  ImGui::SameLine();
  ImGui::TextDisabled(edited_.camera ? "moved" : "scene camera");
  const Vec3 eye = orbit_.eye(), pivot = orbit_.pivot();
  ImGui::TextDisabled("eye %.2f %.2f %.2f  pivot %.2f %.2f %.2f", eye.x, eye.y, eye.z, pivot.x, pivot.y, pivot.z);
  ImGui::Separator();
  if (ImGui::Button("Save image (Ctrl+S)")) saveImage();
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("out/pathlab-<time>.exr (linear) and .png (exposure, clamp, sRGB)");
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F12)")) screenshotRequested_ = true;
  ImGui::PopID();
}

void Viewer::drawPresetSection() {
  ImGui::PushID("presets");
  if (presets_.empty()) {
    ImGui::TextDisabled("none loaded: pathlab view --presets FILE (e.g. assets/presets.json)");
  } else {
    ImGui::TextDisabled("%s (PageUp / PageDown)", presetsPath_.c_str());
    for (size_t i = 0; i < presets_.size(); ++i)
      if (ImGui::Selectable(presets_[i].name.c_str(), static_cast<int>(i) == currentPreset_))
        applyPreset(static_cast<int>(i));
  }
  ImGui::PopID();
}

}  // namespace pathlab::ui
