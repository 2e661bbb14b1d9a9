// The viewer's environment controls carried out: an edit (panel, drop, script) relights the scene
// by reloading it in the background with the new environment, since the lights, and the light
// selection's powers, are built into the immutable Scene. The camera is kept (as for F5).
#include "ui/viewer.h"

#include <chrono>
#include <cstdio>
#include <thread>

namespace pathlab::ui {

void Viewer::editEnvironment(const EnvironmentEdit& edit) {
  apply(edit, environment_.edited);
  if (!edit.spec || edit.spec->empty() || *edit.spec == "none") return;
  // The section's fields show what was chosen, however it was (a drop, a script).
  if (isEnvironmentFile(*edit.spec)) environment_.typedPath = *edit.spec;
  else std::sscanf(edit.spec->c_str(), "%f,%f,%f", &environment_.colour.r, &environment_.colour.g, &environment_.colour.b);
}

void Viewer::openDropped(const std::string& path) {
  if (!isEnvironmentFile(path)) {
    openScene(path);
    return;
  }
  EnvironmentEdit edit;
  edit.spec = path;  // strength and rotation stay: a map swapped for another keeps its setting
  editEnvironment(edit);
}

void Viewer::syncEnvironment() {
  EnvironmentState& e = environment_;
  // One load at a time: edits made meanwhile (a dragged slider) become one more load when it ends,
  // and the UI thread never waits for one.
  if (e.edited == e.applied || scene_.loader.busy()) return;
  scene_.loader.start(scene_.path, e.edited, e.read);
}

void Viewer::finishLoading(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  // Each round takes one finished load; a failed one resets the edit, so this ends.
  while (busy() && std::chrono::steady_clock::now() < end) {
    syncEnvironment();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    pollSceneLoad();
  }
}

bool Viewer::takeLoadedEnvironment(const SceneLoadResult& r) {
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

}  // namespace pathlab::ui
