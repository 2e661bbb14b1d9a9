// Loads a scene on a background thread so the window stays responsive while a large glTF file is
// parsed and its BVH built. A failure is kept as the loader's one-line message; the viewer shows
// it and keeps the previous scene. The environment a scene is lit with is part of its loading
// (lights are built into the Scene), so a new environment is a reload in the background too.
#pragma once

#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"
#include "ui/scene/environment_choice.h"

#include <future>
#include <memory>
#include <optional>
#include <string>

namespace pathlab::ui {

struct SceneLoadResult {
  std::string path;
  std::shared_ptr<const Scene> scene;  // null on failure
  std::string error;                   // "PATH: problem" on failure
  // What it was lit with (set by the start that takes a choice), and the map as read, so the
  // next change of strength or rotation does not read the file again.
  std::optional<EnvironmentChoice> environment;
  std::shared_ptr<const EnvironmentDesc> environmentDesc;
};

class SceneLoader {
 public:
  explicit SceneLoader(LoadOptions options = {}) : options_(options) {}
  // Starts loading `path`; a load still running is waited for and its result dropped.
  void start(const std::string& path);
  // The same, lit with `environment` instead of the options' (reading its map, unless `read`
  // holds it, on the loading thread too: a large EXR takes a while).
  void start(const std::string& path, const EnvironmentChoice& environment,
             std::shared_ptr<const EnvironmentDesc> read);
  bool busy() const { return pending_.valid(); }
  const std::string& pendingPath() const { return pendingPath_; }
  // The result once the load has finished (then the loader is idle again).
  std::optional<SceneLoadResult> poll();
  // Loads synchronously (the first scene, before the window opens).
  static SceneLoadResult load(const std::string& path, const LoadOptions& options = {});

 private:
  LoadOptions options_;
  std::future<SceneLoadResult> pending_;
  std::string pendingPath_;
};

}  // namespace pathlab::ui
