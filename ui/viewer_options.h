// How `pathlab view` starts: scene, initial estimator state, window and headless options. Filled
// by the CLI (app/view_command.cpp), read by runViewer.
#pragma once

#include "core/render/render_settings.h"
#include "core/scene/gltf_loader.h"

#include "core/image/image.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace pathlab::ui {

// The outlier list's rows (ui/inspect/outlier_list.h): by default, and at most.
inline constexpr int kDefaultViewerOutliers = 10;
inline constexpr int kMaxViewerOutliers = 100;

struct ViewerOptions {
  std::string scene;
  LoadOptions load;  // for this scene and every scene opened from the viewer
  // The initial estimator (width and height are ignored: the image follows the window).
  RenderSettings settings;
  int threads = 0;  // render threads, 0: all hardware threads
  int windowWidth = 1280;
  int windowHeight = 720;
  bool lecture = false;  // UI scaled for a projector
  std::string presetsFile;
  std::string preset;    // applied at start (needs presetsFile)
  float exposure = 0.f;  // stops
  uint64_t spp = 0;      // stop accumulating at this many samples per pixel (0: never)
  int pyramidLength = 0; // > 0: open the technique pyramid up to this length
  // The A/B comparison's side B (a converge CONFIG, ui/lane/compare.h): starts side by side.
  std::string compare;
  int outliers = 0;  // > 0: start with the outlier list on, keeping this many (ui/inspect/outlier_list.h)
  std::string techniqueMap;  // start showing this technique map (ui/estimator/technique_map_view.h: parseMapView)
  float renderScale = 1.f;  // render resolution relative to the image area: 1, 0.5 or 0.25
  // Headless: draw offscreen through EGL. frames > 0: close after that many drawn frames (then
  // write the whole viewer to `screenshot` if given); with a window too, for tests.
  bool headless = false;
  int frames = 0;
  std::string screenshot;
  bool force = false;    // overwrite the screenshot; record into a non-empty directory
  // Recording (ui/record/recorder.h): numbered PNG frames of the window (or of the image area alone) in
  // recordDir from the first frame; the F9 key stops and restarts it. recordFps: the clip's rate.
  std::string recordDir;
  bool recordImage = false;
  int recordFps = 30;
  bool hideUi = false;   // start with the panels hidden
  std::string script;    // scripted input (ui/input/input_script.h), counted in drawn frames
  // A reference image (.exr or .pfm) for the live error plot and the error view; rendered at its
  // resolution. errorCsv: write the error series there on exit.
  std::string reference;
  // The reference read by runViewer before any window or GL context opens (a bad file is refused
  // first, and no driver state is left half made); the Viewer reads `reference` itself without it.
  std::shared_ptr<const Image> referenceImage;
  std::string errorCsv;
  bool convergencePanel = false;  // open the convergence panel (plot and technique table)
  bool errorView = false;         // start in the false-colour error view
  std::optional<Technique> zMap;  // the consistency check's |z| map of this technique (settings.checkTechniques)
};

// What can be refused before the scene loads or a window opens, one line each: a technique map
// that does not parse or has no bidirectional tracer, a --compare CONFIG that does not parse.
void checkViewerOptions(const ViewerOptions& options);

}  // namespace pathlab::ui
