// Scene and environment loading in the viewer: the scene shown and its camera orbit, the files
// offered, the environment edited and applied, one load (a scene, or the shown one relit) running in
// the background at a time, and what a finished load says.
#pragma once

#include "ui/message_line.h"
#include "ui/viewer_options.h"
#include "ui/viewer_state.h"

#include <memory>
#include <optional>
#include <string>

namespace pathlab::ui {

// A finished load taken as the shown scene.
struct SceneSwitch {
  bool reload = false;  // the same file again (its view is kept)
  bool relit = false;   // the same file with another environment
};

class SceneController {
 public:
  SceneController(const ViewerOptions& options, std::shared_ptr<const Scene> scene, MessageLine& message);

  const std::shared_ptr<const Scene>& scene() const { return state_.scene; }
  const std::string& path() const { return state_.path; }
  OrbitCamera& orbit() { return state_.orbit; }
  // What the Scene and Environment sections show and edit.
  SceneState& state() { return state_; }
  EnvironmentState& environment() { return environment_; }
  // A load runs or an environment edit waits for one.
  bool busy() const { return state_.loader.busy() || !(environment_.edited == environment_.applied); }

  // Loads `path` in the background, lit as the shown scene is.
  void open(const std::string& path);
  // A dropped .exr / .hdr lights the scene, any other file opens as one.
  void openDropped(const std::string& path);
  // An edit of the environment (the Environment section, a drop, a script): the shown scene is
  // relit in the background, keeping the camera.
  void editEnvironment(const EnvironmentEdit& edit);
  // Starts relighting when the edited environment differs from the shown scene's and no load runs.
  void syncEnvironment();
  // Takes a finished load: the new scene is shown (nothing when none finished, or it failed: the
  // message line says why and the previous scene stays).
  std::optional<SceneSwitch> poll();
  // The message line's account of a switch; `droppedReference` when the viewer dropped one.
  void announce(const SceneSwitch& change, bool droppedReference);
  // The camera orbit back at the scene's own camera.
  void resetOrbit();
  // Rescans the .gltf / .glb files beside the scene and in assets/.
  void refreshFiles();

 private:
  SceneState state_;
  EnvironmentState environment_;
  MessageLine& message_;

  // A finished load's environment becomes the applied one (false: it failed, the edit reverts).
  bool takeLoadedEnvironment(const SceneLoadResult& result);
};

}  // namespace pathlab::ui
