// Scenes and environments loaded in the background: an environment edit relights the scene by
// reloading it with the new environment, since the lights, and the light selection's powers, are
// built into the immutable Scene. The camera is kept (as for F5).
#include "ui/scene/scene_controller.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#ifndef PATHLAB_ASSETS_DIR
#define PATHLAB_ASSETS_DIR "assets"
#endif

namespace pathlab::ui {

SceneController::SceneController(const ViewerOptions& options, std::shared_ptr<const Scene> scene, MessageLine& message)
    : message_(message) {
  state_.scene = std::move(scene);
  state_.path = options.scene;
  state_.loader = SceneLoader(options.load);
  environment_ = EnvironmentState::from(options.load.environment, options.load.lightSelection);
  // A preset's camera: orbit from there.
  state_.orbit = OrbitCamera(options.settings.camera.value_or(state_.scene->cameraDesc()), state_.scene->boundsMin(),
                             state_.scene->boundsMax());
  refreshFiles();
}

void SceneController::open(const std::string& path) {
  // Lit as the shown scene is (the command line's environment, or the one loaded since).
  state_.loader.start(path, environment_.applied, environment_.read);
  message_.show("loading " + path + " ...");
}

void SceneController::openDropped(const std::string& path) {
  if (!isEnvironmentFile(path)) {
    open(path);
    return;
  }
  EnvironmentEdit edit;
  edit.spec = path;  // strength and rotation stay: a map swapped for another keeps its setting
  editEnvironment(edit);
}

void SceneController::editEnvironment(const EnvironmentEdit& edit) {
  apply(edit, environment_.edited);
  if (!edit.spec || edit.spec->empty() || *edit.spec == "none") return;
  // The section's fields show what was chosen, however it was (a drop, a script).
  if (isEnvironmentFile(*edit.spec)) environment_.typedPath = *edit.spec;
  else std::sscanf(edit.spec->c_str(), "%f,%f,%f", &environment_.colour.r, &environment_.colour.g, &environment_.colour.b);
}

void SceneController::syncEnvironment() {
  EnvironmentState& e = environment_;
  // One load at a time: edits made meanwhile (a dragged slider) become one more load when it ends,
  // and the UI thread never waits for one.
  if (e.edited == e.applied || state_.loader.busy()) return;
  state_.loader.start(state_.path, e.edited, e.read);
}

std::optional<SceneSwitch> SceneController::poll() {
  std::optional<SceneLoadResult> r = state_.loader.poll();
  if (!r) return std::nullopt;
  SceneSwitch change;
  change.relit = r->path == state_.path && r->environment && !(*r->environment == environment_.applied);
  if (!takeLoadedEnvironment(*r)) {
    message_.show(r->error + (change.relit ? " (the previous environment is kept)" : " (the previous scene is kept)"),
                  true);
    return std::nullopt;
  }
  // A reload keeps the view (the file is being edited); another scene starts at its own camera.
  change.reload = r->path == state_.path;
  state_.scene = r->scene;
  state_.path = r->path;
  refreshFiles();
  return change;
}

void SceneController::announce(const SceneSwitch& change, bool droppedReference) {
  const Scene& scene = *state_.scene;
  std::string text =
      change.relit ? "environment: " + describe(environment_.applied)
                   : fmt::format("loaded {}: {} triangles, {} lights, {:.1f} MB of geometry", state_.path,
                                 scene.triangleCount(), scene.lights().size(), double(scene.geometryBytes()) / 1e6);
  for (const std::string& w : scene.warnings()) text += "; warning: " + w;
  if (droppedReference)
    text += change.relit ? "; the reference was dropped (it was lit otherwise)"
                         : "; the reference was dropped (it showed the previous scene)";
  // A relight right after a failed one (its strength, say) must not hide the error unread.
  if (change.relit && !message_.error().empty()) return;
  message_.show(text);
}

bool SceneController::takeLoadedEnvironment(const SceneLoadResult& r) {
  EnvironmentState& e = environment_;
  if (!r.scene) {
    // The shown scene keeps its environment and the panel shows it again (a retry would only fail
    // again): a map that failed is dropped from the edit, strength and rotation edited meanwhile
    // stay; anything else reverts the whole edit, so this always ends.
    const bool mapFailed = r.environment && r.environment->spec == e.edited.spec && e.edited.spec != e.applied.spec;
    if (mapFailed) e.edited.spec = e.applied.spec;
    else e.edited = e.applied;
    return false;
  }
  if (r.environment) {
    e.applied = *r.environment;
    e.read = r.environmentDesc;
  }
  return true;
}

void SceneController::resetOrbit() {
  state_.orbit = OrbitCamera(state_.scene->cameraDesc(), state_.scene->boundsMin(), state_.scene->boundsMax());
}

void SceneController::refreshFiles() {
  std::vector<std::string>& files = state_.files;
  files.clear();
  std::vector<std::filesystem::path> dirs = {std::filesystem::path(state_.path).parent_path(), PATHLAB_ASSETS_DIR};
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (dir.empty() || !std::filesystem::is_directory(dir, ec)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".gltf" && ext != ".glb") continue;
      std::string p = std::filesystem::relative(entry.path(), ec).string();
      if (ec || p.empty() || p.starts_with("../../")) p = entry.path().string();
      if (std::find(files.begin(), files.end(), p) == files.end()) files.push_back(p);
    }
  }
  std::sort(files.begin(), files.end());
}

}  // namespace pathlab::ui
