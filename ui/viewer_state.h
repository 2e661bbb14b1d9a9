// The viewer's state, one small struct per concern. The Viewer (ui/viewer.h) and its controllers own
// one of each; the panels (ui/panels/panels.h) are functions over the structs they edit.
#pragma once

#include "core/converge/error_tracker.h"
#include "core/render/progressive_renderer.h"
#include "ui/display/display_settings.h"
#include "ui/estimator/technique_map_view.h"
#include "ui/gl/texture.h"
#include "ui/message_line.h"
#include "ui/presets/presets.h"
#include "ui/scene/environment_choice.h"
#include "ui/scene/orbit_camera.h"
#include "ui/scene/scene_loader.h"

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pathlab::ui {

// Rendering besides the estimator: pausing, the sample target, the render resolution (each side's
// renderer and its answer are a RenderLane's, ui/lane/render_lane.h).
struct RunState {
  bool userPaused = false;
  uint64_t targetSpp = 0;       // stop at this many samples per pixel (0: never)
  float resolutionScale = 1.f;  // render resolution relative to the image area: 1, 0.5 or 0.25
};

// The technique grid's own state beside the estimator it edits.
struct TechniqueGridState {
  int oneLength = 2;      // the "one length only" preset's length (clamped to the maximum where used)
  std::string specError;  // a SPEC typed in the field that does not parse
  // The consistency check's |z| per block drawn over the image for this technique (none: off).
  std::optional<Technique> zMap;
};

// The scene shown, the one loading, the files offered, and the camera moved over it.
struct SceneState {
  std::shared_ptr<const Scene> scene;
  std::string path;
  SceneLoader loader;
  std::vector<std::string> files;  // .gltf / .glb beside the scene and in assets/
  std::string typedPath;
  OrbitCamera orbit;
};

// The environment the scene is lit with (applied: the shown scene was loaded with it) and the one
// the Environment section edits; when they differ and no load is running, the scene is reloaded
// with the edited one in the background (a slider dragged during a load coalesces into one more).
struct EnvironmentState {
  EnvironmentChoice edited, applied;
  std::shared_ptr<const EnvironmentDesc> read;  // applied's map as read (null: none or a colour)
  std::string typedPath;
  Vec3 colour{1.f};  // the uniform colour offered, kept while a map is shown

  // The command line's environment (LoadOptions::environment, null for none), read already.
  static EnvironmentState from(const std::shared_ptr<const EnvironmentDesc>& commandLine,
                               LightSelection lightSelection = LightSelection::Auto) {
    EnvironmentState s;
    s.edited = s.applied = choiceOf(commandLine.get(), lightSelection);
    s.read = commandLine;
    if (commandLine && commandLine->isConstant()) s.colour = commandLine->constant;
    else if (commandLine) s.typedPath = commandLine->source;
    return s;
  }
};

struct PresetState {
  std::vector<NamedPreset> presets;
  std::string path;
  int current = -1;  // the preset applied last, -1 for none
};

// The reference the error is measured against; the tracker is shared with the render thread,
// which measures after each pass.
struct ReferenceState {
  std::shared_ptr<ErrorTracker> errors = std::make_shared<ErrorTracker>();
  std::string typedPath;
  bool matchSize = true;         // render at the reference's resolution
  uint64_t uploadedVersion = 0;  // ErrorTracker::referenceVersion of the reference texture
  std::string status;            // why the error cannot be computed now ("" when it can)
};

// The convergence panel: the error plot's options and the series it draws.
struct ConvergenceState {
  bool show = false;
  ErrorMetric metric = ErrorMetric::RelMse;
  bool againstSpp = false;
  bool slope = true;
  int maxSeries = 8;
  std::vector<ErrorSeries> series;  // a copy, refreshed when the tracker's version changes
  uint64_t seriesVersion = 0;
};

// The technique pyramid panel: what it shows and how large (set by its layout each frame).
struct PyramidView {
  bool show = false;
  int length = 3;
  bool unweighted = false;             // the one shown when there is room for one pyramid only
  bool ownExposure = true;             // each thumbnail auto-exposed, or all at the image's exposure
  Vec2 thumbnail{72.f, 72.f};          // size of one thumbnail on screen
  bool both = false;                   // room for the weighted and the unweighted pyramid
};

// The pyramid's thumbnails as the renderer published them and as textures, tone mapped with
// `toned` (re-toned when the display changes).
struct PyramidImages {
  std::vector<TechniqueThumbnail> thumbnails;
  std::vector<Texture> textures;  // weighted and unweighted per thumbnail
  uint64_t version = 0;
  int side = 128;  // asked of the renderer (its default)
  DisplaySettings toned;
  bool tonedOwnExposure = true;
  std::chrono::steady_clock::time_point lastPoll{};
  // The texture of technique x (a connection or a merge), or null when it has not arrived yet.
  const Texture* texture(Technique x, bool unweighted) const;
  // The renderer publishes merges' thumbnails too (its technique set has merges).
  bool hasMerges() const;
  bool hasEquiangular() const;
};

// The technique maps' luminances as the renderer published them, and the texture of the map
// chosen (recoloured when the luminances or the choice change).
struct MapImages {
  TechniqueLuminance lum;
  uint64_t version = 0;
  Texture texture;
  MapView coloured;
  std::chrono::steady_clock::time_point lastPoll{};
};

// The window's own state: which parts are shown, requests to the frame loop, the message line.
struct UiState {
  bool showUi = true, showHelp = false;
  float scale = 1.f;  // 2 in lecture mode, times the display's HiDPI factor
  bool quit = false, screenshotRequested = false, recordingToggleRequested = false;
  bool recording = false;  // transient notices are left out of the recorded frames
  bool view3dExportRequested = false;
  bool dragging = false;  // a drag that started over the image moves the camera
  bool dragging3D = false;  // ... over the 3D view: its own camera
  Vec2 pressAt{0.f};      // where the left button went down over the image (a click picks a pixel)
  bool pressOverImage = false;
  double frameMs = 0.0;
  MessageLine message;
};

}  // namespace pathlab::ui
