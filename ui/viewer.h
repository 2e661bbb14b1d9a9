// The viewer: two RenderLanes (side A, and side B of the A | B comparison, ui/lane/), the
// controllers of the scene, the inspector and 3D view, and the presets, and one small state struct
// per concern (ui/viewer_state.h). Each frame it lays out the window, draws the panels, which are
// functions over the state they edit (ui/panels/panels.h), carries out what they ask, turns every
// estimator change into one setSettings call per side (a new generation, within the frame) and
// shows the newest snapshots at a bounded rate. One instance per window; all calls on the UI
// thread, between ImGui::NewFrame and ImGui::Render except drawImage.
#pragma once

#include "core/render/progressive_renderer.h"
#include "ui/display/image_rect.h"
#include "ui/estimator/estimator_state.h"
#include "ui/estimator/technique_images.h"
#include "ui/inspect/inspector_controller.h"
#include "ui/lane/compare.h"
#include "ui/lane/render_lane.h"
#include "ui/lane/sides.h"
#include "ui/panels/panels.h"
#include "ui/presets/preset_controller.h"
#include "ui/scene/scene_controller.h"
#include "ui/viewer_options.h"
#include "ui/viewer_state.h"

#include <chrono>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pathlab::ui {

class Viewer {
 public:
  Viewer(const ViewerOptions& options, std::shared_ptr<const Scene> scene, std::vector<NamedPreset> presets);
  ~Viewer();
  // The scene shown (the last one loaded).
  const Scene& shownScene() const { return scene(); }

  // Builds one UI frame: input, panels, settings to the renderer, newest snapshot to the texture.
  void buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths);
  // Takes the newest snapshot (and pyramid) if one is due, outside the ImGui frame; returns
  // whether anything new was uploaded, i.e. whether a frame should be drawn.
  bool pollImage();
  // True while something changes without input (a scene loading): keep drawing frames.
  bool busy() const { return scenes_.busy(); }
  // An edit of the environment (as the Environment section makes them; scripts, tests): the scene
  // is relit in the background, keeping the camera (SceneController).
  void editEnvironment(const EnvironmentEdit& edit) { scenes_.editEnvironment(edit); }
  // Headless scripts (FRAME:wait=SPP, the last frame): waits up to `seconds` for the scene or
  // environment being loaded and shows it, so the samples waited for are the new scene's.
  void finishLoading(double seconds);
  // Draws the image under the panels (after ImGui::Render, before ImGui's draw data).
  void drawImage(Vec2i framebufferSize);
  // The sides of the image: A, and B of the comparison (running only while it is on). drawn()
  // says where the last drawImage put each (empty when nothing was drawn): what a screenshot shows.
  RenderLane& a() { return sides_.a(); }
  RenderLane& b() { return sides_.b(); }
  const RenderLane& a() const { return sides_.a(); }
  const RenderLane& b() const { return sides_.b(); }

  // Row `row` (from 0) of the outlier list in the path inspector and the 3D view (a click on it,
  // the script's outlier=K); a message when there is no such row.
  void openOutlierRow(int row);

  // Headless screenshots: waits (up to `seconds`) until the thumbnails of the current generation's
  // newest pass are published, when the pyramid is shown.
  void waitForPyramid(double seconds);
  // The next frame takes the newest snapshot and pyramid whatever the refresh interval.
  void forceRefresh() { forceRefresh_ = true; }
  bool quitRequested() const { return ui_.quit; }
  bool takeScreenshotRequest() { return std::exchange(ui_.screenshotRequested, false); }
  bool takeRecordingToggleRequest() { return std::exchange(ui_.recordingToggleRequested, false); }
  // The settings of the image shown: its snapshot's once one arrived, else those last applied.
  const RenderSettings& shownSettings() const {
    return a().snapshot().settings.width > 0 ? a().snapshot().settings : a().applied();
  }
  // Where the 3D view was drawn in the last frame (nothing when it is off).
  std::optional<PixelRect> drawnView3D() const { return inspect_.drawnView3D(); }
  // Where the 3D view was drawn when its export (Ctrl+E) was asked for, else nothing: the caller
  // reads it back after the frame is drawn and writes it as a PNG.
  std::optional<PixelRect> takeView3DExportRequest() {
    if (!std::exchange(ui_.view3dExportRequested, false) || !inspect_.view3d.on || inspect_.view3dRect.size.x <= 0)
      return std::nullopt;
    return inspect_.view3dRect;
  }
  // While recording, transient (non-error) messages are not drawn: they would end up in the clip.
  void setRecording(bool recording) { ui_.recording = recording; }
  // The image area of the last built frame, framebuffer pixels from the top left.
  Vec2i imageOrigin() const { return a().rect.origin; }
  Vec2i imageSize() const { return a().rect.size; }
  // Size of the UI relative to the default: 2 in lecture mode, times the display's HiDPI factor.
  void setUiScale(float scale) { ui_.scale = scale; }
  void setFrameTime(double ms) { ui_.frameMs = ui_.frameMs == 0.0 ? ms : 0.9 * ui_.frameMs + 0.1 * ms; }
  void showMessage(const std::string& text, bool error = false);
  // The error line the panel shows ("" when none): headless runs report it on exit.
  std::string shownError() const { return ui_.message.error(); }
  const ErrorTracker& errors() const { return *reference_.errors; }
  // Writes the error series as CSV (ErrorTracker::csv); throws std::runtime_error naming the file.
  void writeErrorCsv(const std::string& path, bool force) const;

 private:
  // The state the panels edit, one struct per concern.
  EstimatorState estimator_;
  TechniqueGridState grid_;
  RunState run_;
  SceneController scenes_;  // the scene shown, its environment, loads in the background
  PresetController presets_;
  DisplaySettings display_;
  ReferenceState reference_;
  ConvergenceState convergence_;
  PyramidView pyramid_;
  MapView maps_;
  CompareState compare_;
  InspectorController inspect_;  // the path inspector and the 3D view
  OutlierListState outliers_;
  UiState ui_;
  EstimatorWarning warning_;  // of the shown image's settings

  // The two sides, each a renderer with what it was given and the image it published; A's
  // pyramid and maps.
  Sides sides_;
  TechniqueImages techniqueImages_;
  // The Metropolis chains' time density of A's last snapshot, coloured (EstimatorState::showChainDensity).
  struct ChainDensityImage {
    Texture texture;
    uint64_t version = ~uint64_t{0};  // the snapshot it was made from
  } chainDensity_;
  void drawChainDensity(float framebufferScale);
  std::chrono::steady_clock::time_point lastPriorityCheck_{};
  bool forceRefresh_ = false;

  // viewer.cpp: the frame (its layout, panels and overlays) and the sides' settings.
  // Where the panels go (ImGui coordinates) and the image's aspect; the sides' and the 3D view's
  // rectangles are set from it.
  struct FrameLayout {
    std::optional<float> aspect;
    float panelWidth = 0.f, pyramidWidth = 0.f, upper = 0.f, bottom = 0.f;
  };
  FrameLayout layOut(Vec2i framebufferSize, float framebufferScale);
  void drawPanels(const FrameLayout& layout, PanelRequests& requests);
  void drawSidePanel(float width, float height, PanelRequests& requests);
  // The captions over each side, the technique map and the inspector's overlays, the 3D view.
  void drawOverImages();
  // The image's size follows its area of the window (or the reference); the pyramid and maps
  // follow what is shown.
  void fitEstimatorToFrame(std::optional<float> aspect, float framebufferScale);
  // What a side's new renderer starts with: the sample target and the thumbnails' size.
  Sides::Start laneStart() const;
  // The settings the panels ask of a side: A's estimator; B's in A's view (compareRenderSettings).
  RenderSettings wantedSettings(const RenderLane& lane) const;
  // Starts or ends side B when compare_.on changed (Sides::setComparing).
  void syncCompare();
  void swapCompareSides();
  // An orthographic scene camera refuses light tracing and a lens: the estimator falls back to
  // bpt and a pinhole, with a message.
  void fitEstimatorToCamera();
  void carryOut(const PanelRequests& requests);
  // Every running side: the settings asked for, then pause, target and timing.
  void applySettings();
  void syncRenderers();
  // Width / height of the image: the reference's when it sets the size, else the camera's (none:
  // the glTF camera has no aspectRatio, the image fills the room as glTF asks).
  std::optional<float> imageAspect() const;
  const Scene& scene() const { return *scenes_.scene(); }
  // A finished load shown on every side; the reference of the previous scene dropped.
  void pollSceneLoad();
  void resetCamera();
  PresetTarget presetTarget();
  // viewer_reference.cpp
  void loadReference(const std::string& path);  // a message in the UI on failure
  void useImageAsReference();
  void returnToReferenceView();
  void updateReferenceState();
  DisplaySettings shownDisplay() const;
  std::string errorViewProblem() const;
  void exportErrorCsv();
  // viewer_input.cpp
  void handleShortcuts();
  void handleCamera(float framebufferScale);
  void perform(Action action);
};

}  // namespace pathlab::ui
