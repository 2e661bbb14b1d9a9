// Loads a scene on a background thread so the window stays responsive while a large glTF file is
// parsed and its BVH built. A failure is kept as the loader's one-line message; the viewer shows
// it and keeps the previous scene.
#pragma once

#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"

#include <future>
#include <memory>
#include <optional>
#include <string>

namespace pathlab::ui {

struct SceneLoadResult {
  std::string path;
  std::shared_ptr<const Scene> scene;  // null on failure
  std::string error;                   // "PATH: problem" on failure
};

class SceneLoader {
 public:
  explicit SceneLoader(LoadOptions options = {}) : options_(options) {}
  // Starts loading `path`; a load still running is waited for and its result dropped.
  void start(const std::string& path);
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
