// The viewer: owns the progressive renderer and the scene, keeps the settings the UI edits, turns
// every estimator change into one setSettings call (a new generation, within the frame), shows the
// newest snapshot at a bounded rate, and draws the panels. One instance per window; all calls on
// the UI thread, between ImGui::NewFrame and ImGui::Render except drawImage.
#pragma once

#include "core/converge/error_tracker.h"
#include "core/render/progressive_renderer.h"
#include "ui/display_settings.h"
#include "ui/image_view.h"
#include "ui/orbit_camera.h"
#include "ui/presets.h"
#include "ui/scene_loader.h"
#include "ui/shortcuts.h"
#include "ui/texture.h"
#include "ui/viewer_options.h"

#include <imgui.h>

#include <chrono>
#include <utility>
#include <memory>
#include <string>
#include <vector>

namespace pathlab::ui {

class Viewer {
 public:
  Viewer(const ViewerOptions& options, std::shared_ptr<const Scene> scene, std::vector<NamedPreset> presets);
  ~Viewer();

  // Builds one UI frame: input, panels, settings to the renderer, newest snapshot to the texture.
  void buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths);
  // Takes the newest snapshot (and pyramid) if one is due, outside the ImGui frame; returns
  // whether anything new was uploaded, i.e. whether a frame should be drawn.
  bool pollImage();
  // True while something changes without input (a scene loading): keep drawing frames.
  bool busy() const { return loader_.busy(); }
  // Draws the image under the panels (after ImGui::Render, before ImGui's draw data).
  void drawImage(Vec2i framebufferSize);

  // Headless screenshots: waits (up to `seconds`) until the thumbnails of the current generation's
  // newest pass are published, when the pyramid is shown.
  void waitForPyramid(double seconds);
  // The next frame takes the newest snapshot and pyramid whatever the refresh interval.
  void forceRefresh() { forceRefresh_ = true; }
  ProgressiveRenderer& renderer() { return *renderer_; }
  bool quitRequested() const { return quit_; }
  bool takeScreenshotRequest() { return std::exchange(screenshotRequested_, false); }
  // Size of the UI relative to the default: 2 in lecture mode, times the display's HiDPI factor.
  void setUiScale(float scale) { uiScale_ = scale; }
  void setFrameTime(double ms) { frameMs_ = frameMs_ == 0.0 ? ms : 0.9 * frameMs_ + 0.1 * ms; }
  void showMessage(const std::string& text, bool error = false);
  const RenderSnapshot& shownSnapshot() const { return snapshot_; }
  const ErrorTracker& errors() const { return *errors_; }
  // Writes the error series as CSV (ErrorTracker::csv); throws std::runtime_error naming the file.
  void writeErrorCsv(const std::string& path, bool force) const;

 private:
  // Estimator state
  std::unique_ptr<ProgressiveRenderer> renderer_;
  std::shared_ptr<const Scene> scene_;
  std::string scenePath_;
  RenderSettings edited_;   // what the panels show
  RenderSettings applied_;  // last handed to the renderer (or refused by it)
  std::string settingsError_;
  std::string specError_;  // a SPEC typed in the grid that does not parse
  bool userPaused_ = false;
  bool idleForNoTechnique_ = false;
  uint64_t targetSpp_ = 0;
  int isolateS_ = 1, isolateT_ = 2;  // the technique the isolate modes show
  int oneLength_ = 2;                // the length of the "one length only" preset
  float resolutionScale_ = 1.f;

  // Scene
  SceneLoader loader_;
  std::vector<std::string> sceneFiles_;
  std::string typedScenePath_;
  OrbitCamera orbit_;

  // Presets
  std::vector<NamedPreset> presets_;
  std::string presetsPath_;
  int currentPreset_ = -1;

  // Display
  DisplaySettings display_;
  std::unique_ptr<ImageView> imageView_;
  RenderSnapshot snapshot_;
  std::chrono::steady_clock::time_point lastPoll_{}, lastPriorityCheck_{};
  bool forceRefresh_ = false;
  Vec2i imageOrigin_{0}, imageSize_{0};  // framebuffer pixels

  // Reference, error series and the convergence panel (panel_reference.cpp, panel_convergence.cpp)
  std::shared_ptr<ErrorTracker> errors_;
  std::string typedReferencePath_;
  bool matchReferenceSize_ = true;     // render at the reference's resolution
  uint64_t uploadedReference_ = 0;     // ErrorTracker::referenceVersion of the reference texture
  std::string referenceStatus_;        // why the error cannot be computed now ("" when it can)
  bool referenceValid_ = false;        // for the shown image
  bool showConvergence_ = false;
  ErrorMetric plotMetric_ = ErrorMetric::RelMse;
  bool plotAgainstSpp_ = false;
  bool plotSlope_ = true;
  int maxSeries_ = 8;
  std::vector<ErrorSeries> series_;  // a copy, refreshed when the tracker's version changes
  uint64_t seriesVersion_ = 0;
  bool timingOn_ = false;

  // Technique pyramid
  bool showPyramid_ = false;
  int pyramidLength_ = 3;
  bool pyramidUnweighted_ = false;
  Vec2 pyramidThumbnail_{72.f, 72.f};  // size of one thumbnail on screen
  bool pyramidBoth_ = false;           // room for the weighted and the unweighted pyramid
  int thumbnailSide_ = 128;            // asked of the renderer (its default)
  bool pyramidOwnExposure_ = true;     // each thumbnail auto-exposed, or all at the image's exposure
  DisplaySettings thumbnailDisplay_;   // what the thumbnail textures were tone mapped with
  bool thumbnailOwnExposure_ = true;
  std::vector<TechniqueThumbnail> thumbnails_;
  std::vector<Texture> thumbnailTextures_;  // weighted and unweighted per thumbnail
  uint64_t pyramidVersion_ = 0;
  std::chrono::steady_clock::time_point lastPyramidPoll_{};

  // UI
  bool showUi_ = true, showHelp_ = false;
  float uiScale_ = 1.f;
  bool quit_ = false, screenshotRequested_ = false;
  bool dragging_ = false;
  double frameMs_ = 0.0;
  std::string message_;
  bool messageIsError_ = false;
  std::chrono::steady_clock::time_point messageTime_{};

  // viewer.cpp: settings, scene and image plumbing
  void applySettings();
  bool updateImage();
  bool updatePyramid();
  void openScene(const std::string& path);
  void pollSceneLoad();
  void refreshSceneFiles();
  void resetCamera();
  void applyPreset(int index);
  void saveImage();
  void loadReference(const std::string& path);  // a message in the UI on failure
  void useImageAsReference();
  void returnToReferenceView();
  void updateReferenceState();
  DisplaySettings shownDisplay() const;
  // viewer_input.cpp
  void handleShortcuts();
  void handleCamera(float framebufferScale);
  void perform(Action action);
  void setIsolateTarget(int s, int t);
  // panels_*.cpp
  void drawSidePanel(float width, float height);
  void drawStatusSection();
  void drawEstimatorSection();
  void drawTechniqueGrid();
  void drawDisplaySection();
  void drawSceneSection();
  void drawPresetSection();
  void drawReferenceSection();
  void drawErrorBar(const DisplaySettings& d);
  void drawErrorBarOverlay(ImVec2 imageOrigin, ImVec2 imageSize);
  float convergencePanelHeight(float windowHeight) const;
  void drawConvergenceWindow(float y, float width, float height);
  void drawTechniqueTable();
  void exportErrorCsv();
  void drawHelpWindow();
  // Width of the pyramid panel for the space left of the window; sets pyramidThumbnail_.
  float pyramidPanelWidth(float availableWidth, float height);
  void drawPyramidWindow(float x, float width, float height);
  void drawPyramid(bool unweighted);
  void drawImageOverlay();
};

}  // namespace pathlab::ui
