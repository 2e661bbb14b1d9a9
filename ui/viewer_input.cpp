// Keyboard shortcuts and the mouse / WASD camera. ImGui keeps the input it uses: nothing here acts
// while a widget wants the mouse or the keyboard.
#include "ui/viewer.h"

#include "core/sampling/technique_label.h"

#include "ui/estimator/technique_grid.h"
#include "ui/record/save_images.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/core.h>
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

void Viewer::openOutlierRow(int row) {
  if (row < 0 || row >= static_cast<int>(outliers_.rows.size())) {
    showMessage(outliers_.rows.empty() ? "the outlier list is empty (Outliers section: find the brightest contributions)"
                                       : fmt::format("the outlier list has no row {}", row + 1),
                true);
    return;
  }
  const Outlier& o = outliers_.rows[static_cast<size_t>(row)].o;
  openOutlier(inspect_.inspector, o, outliers_.list.settings);
  outliers_.opened = row;
  if (!inspect_.view3d.on) perform(Action::ToggleView3D);
  showMessage(fmt::format("outlier {}: {} of pixel {},{} sample {}", row + 1, techniqueLabel(o.technique), o.id.x,
                          o.id.y, o.id.sample));
}

void Viewer::perform(Action action) {
  EstimatorState& e = estimator_;
  auto setTechniques = [&](TechniquePreset preset) {
    if (e.settings.integrator == IntegratorKind::Pt) e.settings.integrator = IntegratorKind::Bpt;
    e.settings.techniques = presetTechniques(preset, std::min(grid_.oneLength, e.settings.maxLength));
  };
  // A merge moves among the merges (its kind stays): M(s + 1, t - 1) is the next merge of its length.
  auto moveIsolated = [&](int ds, int dt) {
    setIsolated(e, {e.isolated.s + ds, e.isolated.t + dt, e.isolated.kind});
  };
  switch (action) {
    case Action::TogglePause: run_.userPaused = !run_.userPaused; break;
    case Action::ToggleUi: ui_.showUi = !ui_.showUi; break;
    case Action::ToggleHelp: ui_.showHelp = !ui_.showHelp; break;
    case Action::TogglePyramid: pyramid_.show = !pyramid_.show; break;
    case Action::TechniquesAll: setTechniques(TechniquePreset::All); break;
    case Action::TechniquesPathTracing: setTechniques(TechniquePreset::PathTracing); break;
    case Action::TechniquesLightTracing: setTechniques(TechniquePreset::LightTracing); break;
    case Action::TechniquesOneLength: setTechniques(TechniquePreset::OneLength); break;
    case Action::TechniquesClear: setTechniques(TechniquePreset::Clear); break;
    case Action::CycleMode: cycleMode(e); break;
    case Action::CycleHeuristic:
      e.settings.mis.heuristic = static_cast<MisHeuristic>((static_cast<int>(e.settings.mis.heuristic) + 1) % kMisHeuristicCount);
      // Metropolis has no passes of independent samples to estimate variance-aware factors from.
      if (e.settings.integrator == IntegratorKind::Mlt && e.settings.mis.heuristic == MisHeuristic::VarianceAware)
        e.settings.mis.heuristic = MisHeuristic::Balance;
      // Optimal MIS corrects the bidirectional path tracer's connections only.
      if (e.settings.integrator != IntegratorKind::Bpt && e.settings.mis.heuristic == MisHeuristic::Optimal)
        e.settings.mis.heuristic = MisHeuristic::Balance;
      break;
    case Action::CycleIntegrator: {
      constexpr IntegratorKind order[] = {IntegratorKind::Bpt, IntegratorKind::Pt, IntegratorKind::Lt, IntegratorKind::Mlt};
      const auto* it = std::find(std::begin(order), std::end(order), e.settings.integrator);
      e.settings.integrator = order[(static_cast<size_t>(it - std::begin(order)) + 1) % std::size(order)];
      if (e.settings.integrator == IntegratorKind::Mlt) {
        e.mode = EstimatorMode::Combine;  // it isolates nothing
        if (e.settings.mis.heuristic == MisHeuristic::VarianceAware) e.settings.mis.heuristic = MisHeuristic::Balance;
      }
      if (e.settings.integrator != IntegratorKind::Bpt && e.settings.mis.heuristic == MisHeuristic::Optimal)
        e.settings.mis.heuristic = MisHeuristic::Balance;
      break;
    }
    case Action::LongerPaths: setMaxLength(e, std::min(e.settings.maxLength + 1, 64)); break;
    case Action::ShorterPaths: setMaxLength(e, std::max(e.settings.maxLength - 1, 1)); break;
    case Action::IsolateMoreLight: moveIsolated(+1, -1); break;
    case Action::IsolateMoreCamera: moveIsolated(-1, +1); break;
    case Action::IsolateLonger: moveIsolated(0, +1); break;
    case Action::IsolateShorter: moveIsolated(0, -1); break;
    case Action::IsolateS0: case Action::IsolateS1: case Action::IsolateS2: case Action::IsolateS3:
    case Action::IsolateS4: case Action::IsolateS5: case Action::IsolateS6: case Action::IsolateS7:
    case Action::IsolateS8: case Action::IsolateS9: {
      const int s = static_cast<int>(action) - static_cast<int>(Action::IsolateS0);
      if (!isolateOfChosenLength(e, grid_.oneLength, s))
        showMessage(fmt::format("no technique with s = {} at length {} (the grid's k)", s,
                                std::min(grid_.oneLength, e.settings.maxLength)));
      break;
    }
    case Action::NextPreset: presets_.next(presetTarget()); break;
    case Action::PreviousPreset: presets_.previous(presetTarget()); break;
    case Action::ExposureUp: display_.exposure = std::min(display_.exposure + 0.5f, 20.f); break;
    case Action::ExposureDown: display_.exposure = std::max(display_.exposure - 0.5f, -20.f); break;
    case Action::ToggleToneMap:
      display_.toneMap = display_.toneMap == ToneMap::Clamp ? ToneMap::Filmic : ToneMap::Clamp;
      break;
    case Action::ToggleFalseColour: display_.falseColour = !display_.falseColour; break;
    case Action::ToggleConvergence: convergence_.show = !convergence_.show; break;
    case Action::ToggleErrorView:
      display_.errorView = !display_.errorView;
      if (display_.errorView && !reference_.errors->reference())
        showMessage("the error view needs a reference (Ctrl+R takes the image)", true);
      break;
    case Action::UseImageAsReference: useImageAsReference(); break;
    case Action::ResetCamera: resetCamera(); break;
    case Action::ReloadScene: scenes_.open(scenes_.path()); break;
    case Action::SaveImage: saveImages(a(), b(), display_.exposure, ui_.message); break;
    case Action::Screenshot: ui_.screenshotRequested = true; break;
    case Action::ToggleRecording: ui_.recordingToggleRequested = true; break;
    case Action::Quit: ui_.quit = true; break;
    case Action::ToggleCompare:
      if (compare_.on) compare_.on = false;
      // The first time: the seed's comparison, the other integrator against this one.
      else if (!compare_.typed.empty()) compare_.on = true;
      else applyCompareConfig(compare_, e.settings.integrator == IntegratorKind::Pt ? "bpt" : "pt", renderSettings(e));
      break;
    case Action::ToggleInspector:
      inspect_.inspector.on = !inspect_.inspector.on;
      if (inspect_.inspector.on && !inspect_.inspector.pick) showMessage("path inspector: click a pixel of the image");
      break;
    case Action::NextSample:
    case Action::PreviousSample:
      if (!inspect_.inspector.on || !inspect_.inspector.pick) {
        showMessage("pick a pixel first: K, then click the image");
        break;
      }
      if (action == Action::NextSample) ++inspect_.inspector.sample;
      else if (inspect_.inspector.sample > 0) --inspect_.inspector.sample;
      break;
    case Action::BrightestSample:
      if (!inspect_.inspector.on || !inspect_.inspector.pixel || !inspect_.inspector.result) {
        showMessage("pick a pixel first: K, then click the image");
        break;
      }
    {
      const RenderSettings& settings = inspect_.inspector.inspectedSettings;
      const uint64_t n = brightestSearchCount(settings);
      inspect_.inspector.sample = brightestSample(scene(), settings, *inspect_.inspector.pixel, n);
      showMessage(fmt::format("the brightest of the first {} samples is sample {}", n, inspect_.inspector.sample));
    }
      break;
    case Action::ToggleView3D:
      inspect_.view3d.on = !inspect_.view3d.on;
      // One image beside the main one: the 3D view takes the comparison's place.
      if (inspect_.view3d.on && compare_.on) {
        compare_.on = false;
        showMessage("the comparison is off while the 3D view is shown");
      }
      break;
    case Action::ToggleParticles:
      inspect_.view3d.particles.on = !inspect_.view3d.particles.on;
      if (inspect_.view3d.particles.on && !inspect_.view3d.on) perform(Action::ToggleView3D);
      break;
    case Action::ExportInspection: inspect_.exportInspection(ui_.message); break;
    case Action::ExportView3D:
      if (inspect_.view3d.on) ui_.view3dExportRequested = true;
      else showMessage("the 3D view is off (O shows it)");
      break;
    case Action::SwapCompareSides:
      if (compare_.on) swapCompareSides();
      else showMessage("nothing to swap: the comparison is off (C turns it on)");
      break;
  }
}

void Viewer::handleCamera(float framebufferScale) {
  const ImGuiIO& io = ImGui::GetIO();
  const Vec2 mouse = Vec2(io.MousePos.x, io.MousePos.y) * framebufferScale;
  // The fitted rectangle: a drag or a wheel over the bars beside a letterboxed image is not the image's.
  const bool overImage = a().rect.contains(mouse) || (b().running() && b().rect.contains(mouse));
  bool moved = false;
  // A drag belongs to the image only if it started there, outside every ImGui window.
  const bool anyDown = io.MouseDown[0] || io.MouseDown[1] || io.MouseDown[2];
  // A click (press and release within a few pixels) on the image picks the inspector's pixel.
  if (ImGui::IsMouseClicked(0)) {
    ui_.pressAt = mouse;
    ui_.pressOverImage = a().rect.contains(mouse) && !io.WantCaptureMouse;
  }
  if (inspect_.inspector.on && ImGui::IsMouseReleased(0) && ui_.pressOverImage && glm::length(mouse - ui_.pressAt) < 4.f &&
      imageSize().x > 0 && imageSize().y > 0) {
    inspect_.inspector.pick = (mouse - Vec2(imageOrigin())) / Vec2(imageSize());
    // A pixel of the image shown, not of an outlier's render.
    inspect_.inspector.pinned.reset();
    inspect_.inspector.pinnedShown.reset();
    inspect_.inspector.sample = 0;
  }
  // The 3D view has a camera of its own: drags and the wheel over it move only that camera.
  const bool over3D = inspect_.view3d.on && inspect_.view3d.orbit && inspect_.view3dRect.contains(mouse) && !io.WantCaptureMouse;
  const bool pressed = ImGui::IsMouseClicked(0) || ImGui::IsMouseClicked(1) || ImGui::IsMouseClicked(2);
  if (!anyDown) ui_.dragging3D = false;
  else if (!ui_.dragging && !ui_.dragging3D && over3D && pressed) ui_.dragging3D = true;
  if (ui_.dragging3D && (io.MouseDelta.x != 0.f || io.MouseDelta.y != 0.f)) {
    const float height = static_cast<float>(std::max(inspect_.view3dRect.size.y, 1)) / framebufferScale;
    const Vec2 d(io.MouseDelta.x / height, io.MouseDelta.y / height);
    if (io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift)) inspect_.view3d.orbit->pan(-d.x, d.y);
    else inspect_.view3d.orbit->orbit(kPi * d.x, -kPi * d.y);
  }
  if (over3D && io.MouseWheel != 0.f) inspect_.view3d.orbit->zoom(io.MouseWheel);
  if (!anyDown) ui_.dragging = false;
  else if (!ui_.dragging && !ui_.dragging3D && overImage && !io.WantCaptureMouse && pressed)
    ui_.dragging = true;
  if (ui_.dragging && (io.MouseDelta.x != 0.f || io.MouseDelta.y != 0.f)) {
    const float height = static_cast<float>(std::max(imageSize().y, 1)) / framebufferScale;
    const Vec2 d(io.MouseDelta.x / height, io.MouseDelta.y / height);
    if (io.MouseDown[2] || (io.MouseDown[0] && io.KeyShift)) scenes_.orbit().pan(-d.x, d.y);
    else scenes_.orbit().orbit(kPi * d.x, -kPi * d.y);  // a drag over the image height turns by half a turn
    moved = true;
  }
  if (overImage && !io.WantCaptureMouse && io.MouseWheel != 0.f) {
    scenes_.orbit().zoom(io.MouseWheel);
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
      scenes_.orbit().fly(fly * (io.KeyShift ? 3.f : 1.f), std::min(io.DeltaTime, 0.1f));
      moved = true;
    }
  }
  if (moved) estimator_.settings.camera = scenes_.orbit().desc();
}

}  // namespace pathlab::ui
