// `pathlab view [SCENE]`: registers the viewer's options and hands them to ui::runViewer.
#include "app/view_command.h"

#include "app/output_check.h"
#include "app/shared_options.h"

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace {

// The bundled scene, found from the working directory or else in the source tree the binary was
// built from (so `build/app/pathlab view` works from anywhere on the build machine).
constexpr const char* kDefaultScene = "assets/cornell-box.gltf";

}  // namespace

namespace pathlab::app {

void addViewCommand(CLI::App& app, ViewOptions& o) {
  CLI::App* cmd = app.add_subcommand("view", "Open the interactive viewer (or, with --headless, screenshot it)");
  ui::ViewerOptions& v = o.viewer;
  v.scene = kDefaultScene;
  addSceneArgument(cmd, v.scene, "the bundled Cornell box");
  addEstimatorOptions(cmd, o.estimator);
  addThreadsOption(cmd, v.threads, "Render");
  addLoadOptions(cmd, v.load, o.environment);
  // The window's size, not the image's (addImageSizeOptions): the image follows the room the panels leave.
  cmd->add_option("--width", v.windowWidth, "Window width in pixels (the image keeps the camera's aspect in the room the panels leave)")
      ->check(CLI::Range(64, kMaxImageSide));
  cmd->add_option("--height", v.windowHeight, "Window height in pixels")->check(CLI::Range(64, kMaxImageSide));
  auto* presets = cmd->add_option("--presets", v.presetsFile, "JSON file of named presets (e.g. assets/presets.json)");
  cmd->add_option("--preset", v.preset, "Start with this named preset (replaces the estimator options)")
      ->needs(presets);
  cmd->add_flag("--lecture", v.lecture, "Lecture mode: UI scaled for a projector");
  cmd->add_option("--exposure", v.exposure, "Display exposure in stops")->check(CLI::Range(-40.f, 40.f));
  // Not a budget (addSampleBudgetOptions): the viewer accumulates until closed, 0 never stops.
  cmd->add_option("--spp", v.spp, "Stop accumulating at this many samples per pixel (headless: the screenshot waits for them)")
      ->check(CLI::Range(0, kMaxSpp));
  cmd->add_option("--pyramid", v.pyramidLength, "Open the technique pyramid up to this path length")
      ->check(CLI::Range(1, kMaxPyramidLength));
  cmd->add_option("--compare", v.compare,
                  "Side by side with a second estimator B, as a converge CONFIG (e.g. pt, bpt:mis=power, "
                  "lt); each side renders on half of the threads");
  cmd->add_option("--outliers", v.outliers,
                  "Open the outlier list: the N brightest weighted contributions of the image's passes, a click "
                  "opening one in the path inspector")
      ->check(CLI::Range(1, ui::kMaxViewerOutliers));
  cmd->add_option("--technique-map", v.techniqueMap,
                  "Show a technique map over the image: dominant, dominant:K, share:S,T or cannot:S,T");
  cmd->add_flag("--hide-ui", v.hideUi, "Start with the panels hidden (Tab shows them)");
  cmd->add_option("--script", v.script,
                  "Scripted input for tests: 'FRAME:key=NAME;FRAME:drag=X0,Y0>X1,Y1;FRAME:wait=SPP' (frames count from 0)");
  auto* headless = cmd->add_flag("--headless", v.headless, "Draw offscreen through EGL (no display needed)");
  (void)headless;
  auto* frames = cmd->add_option("--frames", v.frames, "Close after this many frames (headless default: 60)")
                     ->check(CLI::Range(1, 100000));
  cmd->add_option("--screenshot", v.screenshot, "After the last frame, write the whole viewer to this PNG")
      ->needs(frames);
  auto* record = cmd->add_option("--record", v.recordDir,
                                 "Record numbered PNG frames of the window into this directory from the first frame "
                                 "(F9 stops and restarts; with ffmpeg installed, DIR/recording.mp4 on stop)");
  cmd->add_flag("--record-image", v.recordImage, "Record the image area alone (with its caption), not the whole window")
      ->needs(record);
  cmd->add_option("--record-fps", v.recordFps, "Frame rate of the recording (default 30)")->check(CLI::Range(1, 120));
  cmd->add_option("--render-scale", v.renderScale, "Render resolution relative to the window: 1, 0.5 or 0.25")
      ->check(CLI::IsMember({1.f, 0.5f, 0.25f}));
  cmd->add_option("--reference", v.reference,
                  "Reference image (.exr or .pfm) for the live error plot and the error view; the image is "
                  "rendered at its resolution");
  cmd->add_option("--error-csv", v.errorCsv, "On exit, write every error series to this CSV (needs a reference)");
  cmd->add_flag("--convergence", v.convergencePanel, "Open the convergence panel (error plot, technique rays and time)");
  cmd->add_flag("--error-view", v.errorView, "Start in the false-colour error view (needs --reference)");
  cmd->add_flag("--check", o.estimator.settings.checkTechniques,
                "Run the consistency check of the techniques (cells of those that disagree turn red)");
  cmd->add_option("--z-map", o.zMap, "S,T: with --check, draw technique (S,T)'s |z| per block over the image");
  addForceFlag(cmd, v.force, "the screenshot (and the error CSV) if it exists; record into a non-empty directory");
}

int runView(ViewOptions o) {
  finishEstimatorOptions(o.estimator);
  finishEnvironmentOptions(o.environment, o.viewer.load);
  if (o.viewer.headless && o.viewer.frames == 0) o.viewer.frames = 60;
  o.viewer.settings = o.estimator.settings;
  if (!o.zMap.empty()) {
    int s = -1, t = -1;
    char extra = 0;
    if (std::sscanf(o.zMap.c_str(), "%d,%d%c", &s, &t, &extra) != 2 || !Technique{s, t}.valid() ||
        Technique{s, t}.length() > o.estimator.settings.maxLength)
      throw std::invalid_argument(fmt::format("--z-map: '{}' is not a technique S,T of length 1..{}", o.zMap,
                                              o.estimator.settings.maxLength));
    if (!o.estimator.settings.checkTechniques) throw std::invalid_argument("--z-map needs --check");
    o.viewer.zMap = Technique{s, t};
  }
  ui::checkViewerOptions(o.viewer);  // one line and exit 1 before any window opens
  // Before the viewer loads the scene; it checks the extension and --force itself.
  if (!o.viewer.screenshot.empty()) checkOutputWritable(o.viewer.screenshot);
  if (!o.viewer.errorCsv.empty()) checkOutputWritable(o.viewer.errorCsv);
  if (!o.viewer.recordDir.empty()) checkOutputDirectory(o.viewer.recordDir);
  if (o.viewer.scene == kDefaultScene && !std::filesystem::exists(o.viewer.scene))
    o.viewer.scene = PATHLAB_ASSETS_DIR "/cornell-box.gltf";
  // The render threads get every core; the UI thread still runs at its own bounded frame rate.
  const ThreadLimit threadLimit(o.viewer.threads);
  o.viewer.threads = threadLimit.threads();
  return ui::runViewer(o.viewer);
}

}  // namespace pathlab::app
