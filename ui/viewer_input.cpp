// Keyboard shortcuts and the mouse / WASD camera. ImGui keeps the input it uses: nothing here acts
// while a widget wants the mouse or the keyboard.
#include "ui/viewer.h"

#include "ui/technique_grid.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>

namespace pathlab::ui {

void Viewer::handleShortcuts() {
  const ImGuiIO& io = ImGui::GetIO();
  if (io.WantCaptureKeyboard || io.WantTextInput) return;
  for (const Shortcut& s : shortcuts()) {
    if (s.ctrl != io.KeyCtrl) continue;
    if (ImGui::IsKeyPressed(s.key, false)) perform(s.action);
  }
}

void Viewer::setIsolateTarget(int s, int t) {
  if (s < 0 || t < 1 || s + t - 1 < 1 || s + t - 1 > edited_.maxLength) return;
  isolateS_ = s;
  isolateT_ = t;
  if (edited_.isolate) edited_.isolate->s = s, edited_.isolate->t = t;
}

void Viewer::perform(Action action) {
  auto setTechniques = [&](TechniquePreset preset) {
    if (edited_.integrator == IntegratorKind::Pt) edited_.integrator = IntegratorKind::Bpt;
    edited_.techniques = presetTechniques(preset, oneLength_);
  };
  switch (action) {
    case Action::TogglePause:
      userPaused_ = !userPaused_;
      renderer_->setPaused(userPaused_ || idleForNoTechnique_);
      break;
    case Action::ToggleUi: showUi_ = !showUi_; break;
    case Action::ToggleHelp: showHelp_ = !showHelp_; break;
    case Action::TogglePyramid: showPyramid_ = !showPyramid_; break;
    case Action::TechniquesAll: setTechniques(TechniquePreset::All); break;
    case Action::TechniquesPathTracing: setTechniques(TechniquePreset::PathTracing); break;
    case Action::TechniquesLightTracing: setTechniques(TechniquePreset::LightTracing); break;
    case Action::TechniquesOneLength: setTechniques(TechniquePreset::OneLength); break;
    case Action::TechniquesClear: setTechniques(TechniquePreset::Clear); break;
    case Action::CycleMode: {
      if (edited_.integrator == IntegratorKind::Pt) edited_.integrator = IntegratorKind::Bpt;
      const int next = (static_cast<int>(modeOf(edited_)) + 1) % 3;
      setMode(edited_, static_cast<EstimatorMode>(next), isolateS_, isolateT_);
      break;
    }
    case Action::CycleHeuristic:
      edited_.mis.heuristic = static_cast<MisHeuristic>((static_cast<int>(edited_.mis.heuristic) + 1) % 3);
      break;
    case Action::CycleIntegrator: {
      constexpr IntegratorKind order[] = {IntegratorKind::Bpt, IntegratorKind::Pt, IntegratorKind::Lt};
      const auto* it = std::find(std::begin(order), std::end(order), edited_.integrator);
      edited_.integrator = order[(static_cast<size_t>(it - std::begin(order)) + 1) % 3];
      break;
    }
    case Action::LongerPaths: setMaxLength(edited_, std::min(edited_.maxLength + 1, 64)); break;
    case Action::ShorterPaths:
      setMaxLength(edited_, std::max(edited_.maxLength - 1, 1));
      oneLength_ = std::min(oneLength_, edited_.maxLength);
      if (edited_.isolate) isolateS_ = edited_.isolate->s, isolateT_ = edited_.isolate->t;
      break;
    case Action::IsolateMoreLight: setIsolateTarget(isolateS_ + 1, isolateT_ - 1); break;
    case Action::IsolateMoreCamera: setIsolateTarget(isolateS_ - 1, isolateT_ + 1); break;
    case Action::IsolateLonger: setIsolateTarget(isolateS_, isolateT_ + 1); break;
    case Action::IsolateShorter: setIsolateTarget(isolateS_, isolateT_ - 1); break;
    case Action::NextPreset: applyPreset(currentPreset_ + 1); break;
    case Action::PreviousPreset: applyPreset(currentPreset_ < 0 ? -1 : currentPreset_ - 1); break;
    case Action::ExposureUp: display_.exposure = std::min(display_.exposure + 0.5f, 20.f); break;
    case Action::ExposureDown: display_.exposure = std::max(display_.exposure - 0.5f, -20.f); break;
    case Action::ToggleToneMap:
      display_.toneMap = display_.toneMap == ToneMap::Clamp ? ToneMap::Filmic : ToneMap::Clamp;
      break;
    case Action::ToggleFalseColour: display_.falseColour = !display_.falseColour; break;
    case Action::ToggleConvergence: showConvergence_ = !showConvergence_; break;
    case Action::ToggleErrorView:
      display_.errorView = !display_.errorView;
      if (display_.errorView && !errors_->reference()) showMessage("the error view needs a reference (Ctrl+R takes the image)", true);
      break;
    case Action::UseImageAsReference: useImageAsReference(); break;
    case Action::ResetCamera: resetCamera(); break;
    case Action::ReloadScene: openScene(scenePath_); break;
    case Action::SaveImage: saveImage(); break;
    case Action::Screenshot: screenshotRequested_ = true; break;
    case Action::Quit: quit_ = true; break;
  }
}

void Viewer::handleCamera(float framebufferScale) {
  const ImGuiIO& io = ImGui::GetIO();
  const Vec2 mouse = Vec2(io.MousePos.x, io.MousePos.y) * framebufferScale;
  const bool overImage = mouse.x >= static_cast<float>(imageOrigin_.x) && mouse.y >= static_cast<float>(imageOrigin_.y) &&
                         mouse.x < static_cast<float>(imageOrigin_.x + imageSize_.x) &&
                         mouse.y < static_cast<float>(imageOrigin_.y + imageSize_.y);
  bool moved = false;
  // A drag belongs to the image only if it started there, outside every ImGui window.
  const bool anyDown = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  if (!anyDown) dragging_ = false;
  else if (!dragging_ && overImage && !io.WantCaptureMouse &&
           (ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1) || ImGui::IsMouseClicked(2)))
    dragging_ = true;
  if (dragging_ && (io.MouseDelta.x != 0.f || io.MouseDelta.y != 0.f)) {
    const float height = static_cast<float>(std::max(imageSize_.y, 1)) / framebufferScale;
    const Vec2 d(io.MouseDelta.x / height, io.MouseDelta.y / height);
    if (io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift)) orbit_.pan(-d.x, d.y);
    else orbit_.orbit(kPi * d.x, -kPi * d.y);  // a drag over the image height turns by half a turn
    moved = true;
  }
  if (overImage && !io.WantCaptureMouse && io.MouseWheel != 0.f) {
    orbit_.zoom(io.MouseWheel);
    moved = true;
  }
  if (!io.WantCaptureKeyboard && !io.WantTextInput && !io.KeyCtrl) {
    Vec3 fly(0.f);
    fly.x += io.KeysDown[GLFW_KEY_W] ? 1.f : 0.f;
    fly.x -= io.KeysDown[GLFW_KEY_S] ? 1.f : 0.f;
    fly.y += io.KeysDown[GLFW_KEY_D] ? 1.f : 0.f;
    fly.y -= io.KeysDown[GLFW_KEY_A] ? 1.f : 0.f;
    fly.z += io.KeysDown[GLFW_KEY_E] ? 1.f : 0.f;
    fly.z -= io.KeysDown[GLFW_KEY_Q] ? 1.f : 0.f;
    if (fly != Vec3(0.f)) {
      orbit_.fly(fly * (io.KeyShift ? 3.f : 1.f), std::min(io.DeltaTime, 0.1f));
      moved = true;
    }
  }
  if (moved) edited_.camera = orbit_.desc();
}

}  // namespace pathlab::ui
