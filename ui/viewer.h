// The viewer: owns the progressive renderer, the image and one small state struct per concern
// (ui/viewer_state.h); draws the panels, which are functions over the state they edit
// (ui/panels.h), carries out what they ask, turns every estimator change into one setSettings call
// (a new generation, within the frame) and shows the newest snapshot at a bounded rate. One
// instance per window; all calls on the UI thread, between ImGui::NewFrame and ImGui::Render
// except drawImage.
#pragma once

#include "core/render/progressive_renderer.h"
#include "ui/compare.h"
#include "ui/estimator_state.h"
#include "ui/image_rect.h"
#include "ui/image_view.h"
#include "ui/panels.h"
#include "ui/scene_raster.h"
#include "ui/view3d.h"
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
  const Scene& shownScene() const { return *scene_.scene; }

  // Builds one UI frame: input, panels, settings to the renderer, newest snapshot to the texture.
  void buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths);
  // Takes the newest snapshot (and pyramid) if one is due, outside the ImGui frame; returns
  // whether anything new was uploaded, i.e. whether a frame should be drawn.
  bool pollImage();
  // True while something changes without input (a scene loading): keep drawing frames.
  bool busy() const { return scene_.loader.busy() || !(environment_.edited == environment_.applied); }
  // An edit of the environment (as the Environment section makes them; scripts, tests): the scene
  // is relit in the background, keeping the camera (viewer_environment.cpp).
  void editEnvironment(const EnvironmentEdit& edit);
  // Headless scripts (FRAME:wait=SPP, the last frame): waits up to `seconds` for the scene or
  // environment being loaded and shows it, so the samples waited for are the new scene's.
  void finishLoading(double seconds);
  // Draws the image under the panels (after ImGui::Render, before ImGui's draw data).
  void drawImage(Vec2i framebufferSize);
  // Where the last drawImage put the image (empty when nothing was drawn): what a screenshot shows.
  const PixelRect& drawnImage() const { return drawn_; }
  // The comparison's side B (CompareState): where it was drawn, what it shows; null renderer when off.
  const PixelRect& drawnCompareImage() const { return compareSide_.drawn; }
  const RenderSnapshot& compareSnapshot() const { return compareSide_.snapshot; }
  ProgressiveRenderer* compareRenderer() { return compareSide_.renderer.get(); }

  // Headless screenshots: waits (up to `seconds`) until the thumbnails of the current generation's
  // newest pass are published, when the pyramid is shown.
  void waitForPyramid(double seconds);
  // The next frame takes the newest snapshot and pyramid whatever the refresh interval.
  void forceRefresh() { forceRefresh_ = true; }
  ProgressiveRenderer& renderer() { return *renderer_; }
  bool quitRequested() const { return ui_.quit; }
  bool takeScreenshotRequest() { return std::exchange(ui_.screenshotRequested, false); }
  bool takeRecordingToggleRequest() { return std::exchange(ui_.recordingToggleRequested, false); }
  // Where the 3D view was drawn in the last frame (nothing when it is off).
  std::optional<PixelRect> drawnView3D() const {
    if (!view3dTextureInUse_) return std::nullopt;
    return view3dRect_;
  }
  // Where the 3D view was drawn when its export (Ctrl+E) was asked for, else nothing: the caller
  // reads it back after the frame is drawn and writes it as a PNG.
  std::optional<PixelRect> takeView3DExportRequest() {
    if (!std::exchange(ui_.view3dExportRequested, false) || !view3d_.on || view3dRect_.size.x <= 0) return std::nullopt;
    return view3dRect_;
  }
  // While recording, transient (non-error) messages are not drawn: they would end up in the clip.
  void setRecording(bool recording) { ui_.recording = recording; }
  // The image area of the last built frame, framebuffer pixels from the top left.
  Vec2i imageOrigin() const { return imageOrigin_; }
  Vec2i imageSize() const { return imageSize_; }
  // Size of the UI relative to the default: 2 in lecture mode, times the display's HiDPI factor.
  void setUiScale(float scale) { ui_.scale = scale; }
  void setFrameTime(double ms) { ui_.frameMs = ui_.frameMs == 0.0 ? ms : 0.9 * ui_.frameMs + 0.1 * ms; }
  void showMessage(const std::string& text, bool error = false);
  // The error line the panel shows ("" when none): headless runs report it on exit.
  std::string shownError() const { return ui_.messageIsError ? ui_.message : std::string(); }
  const RenderSnapshot& shownSnapshot() const { return snapshot_; }
  const ErrorTracker& errors() const { return *reference_.errors; }
  // Writes the error series as CSV (ErrorTracker::csv); throws std::runtime_error naming the file.
  void writeErrorCsv(const std::string& path, bool force) const;

 private:
  // The state the panels edit, one struct per concern.
  EstimatorState estimator_;
  TechniqueGridState grid_;
  RunState run_;
  SceneState scene_;
  EnvironmentState environment_;
  PresetState presets_;
  DisplaySettings display_;
  ReferenceState reference_;
  ConvergenceState convergence_;
  PyramidView pyramid_;
  MapView maps_;
  CompareState compare_;
  PathInspectorState inspector_;
  InspectorOverlay inspectorOverlay_;  // of inspector_'s result, recomputed when it replays
  View3DState view3d_;
  std::unique_ptr<SceneRaster> sceneRaster_;  // while the 3D view is shown
  PixelRect view3dRect_;                      // where it goes, framebuffer pixels
  bool view3dTextureInUse_ = false;           // this frame's draw lists show the raster's texture
  PanelRect inspectorRect_;                   // the inspector's window, ImGui coordinates (empty: none)
  UiState ui_;
  EstimatorWarning warning_;  // of the shown image's settings

  // The renderer and what it was last given; the image and the pyramid it published.
  std::unique_ptr<ProgressiveRenderer> renderer_;
  RenderSettings applied_;  // last handed to the renderer (or refused by it)
  bool pausedApplied_ = false, timingApplied_ = false;
  uint64_t targetApplied_ = 0;
  std::unique_ptr<ImageView> imageView_;
  RenderSnapshot snapshot_;
  PyramidImages pyramidImages_;
  MapImages mapImages_;
  std::chrono::steady_clock::time_point lastPoll_{}, lastPriorityCheck_{};
  bool forceRefresh_ = false;
  // The image's rectangle in framebuffer pixels: the room the panels leave, fitted to the image's
  // aspect (ui/image_rect.h). Input, captions and overlays use it; the bars stay background.
  Vec2i imageOrigin_{0}, imageSize_{0};
  PixelRect drawn_;
  int threads_ = 0;  // the render threads asked for (0: all); each side of a comparison gets half

  // Side B of the comparison: a renderer of its own while compare_.on, with what it was given, its
  // image and where it goes. Side A is the fields above.
  struct CompareSide {
    std::unique_ptr<ProgressiveRenderer> renderer;
    RenderSettings applied;
    bool idle = false;  // B enables no technique: black, like A's idleForNoTechnique
    bool pausedApplied = false;
    uint64_t targetApplied = 0;
    std::unique_ptr<ImageView> view;
    RenderSnapshot snapshot;
    std::chrono::steady_clock::time_point lastPoll{};
    PixelRect rect, drawn;
  };
  CompareSide compareSide_;

  // viewer.cpp: the frame, settings to the renderer, images to the textures, scenes, presets, saving
  void drawSidePanel(float width, float height, PanelRequests& requests);
  // A renderer for one side (lane 0: A, 1: B) with the viewer's target, observer and thumbnails.
  std::unique_ptr<ProgressiveRenderer> makeRenderer(const RenderSettings& settings, int lane);
  // The error tracker's observer of the renderer on side `lane` (ErrorTracker::observe).
  PassObserver passObserver(int lane) const;
  // Starts or ends the comparison when compare_.on changed: both sides restart together, each on
  // half of the threads (the main renderer back on all of them when it ends).
  void syncCompare();
  void applyCompareSettings();
  bool updateCompareImage();
  void swapCompareSides();
  // The path inspector: replays the picked sample when it or the shown image's settings changed.
  void updateInspector();
  // The 3D view's particles; its drawing over the triangles (ImGui's lists).
  void updateView3D();
  // An orthographic scene camera refuses light tracing and a lens: the estimator falls back to
  // bpt and a pinhole, with a message.
  void fitEstimatorToCamera();
  void drawView3D(float fbScale);
  // Writes the inspected sample as JSON (Ctrl+J) in out/.
  void exportInspection();
  void carryOut(const PanelRequests& requests);
  void applySettings();
  void syncRenderer();
  bool updateImage();
  bool updatePyramid();
  bool updateMaps();
  // The chosen technique map over the image area, when shown and arrived (ImGui's background).
  void drawMapOverImage(float fbScale);
  // Width / height of the image: the reference's when it sets the size, else the camera's (none:
  // the glTF camera has no aspectRatio, the image fills the room as glTF asks).
  std::optional<float> imageAspect() const;
  void openScene(const std::string& path);
  void pollSceneLoad();
  // viewer_environment.cpp: a dropped .exr / .hdr lights the scene, any other file opens as one.
  void openDropped(const std::string& path);
  // Starts relighting when the edited environment differs from the shown
  // scene's and no load is running; takes a finished load's environment (false: it failed).
  void syncEnvironment();
  bool takeLoadedEnvironment(const SceneLoadResult& result);
  void refreshSceneFiles();
  void resetCamera();
  void applyPreset(int index);
  void saveImage();
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
