// Background scene loading with one-line errors.
#include "ui/scene/scene_loader.h"

#include "core/scene/gltf_loader.h"

#include <chrono>

namespace pathlab::ui {

SceneLoadResult SceneLoader::load(const std::string& path, const LoadOptions& options) {
  SceneLoadResult r;
  r.path = path;
  try {
    r.scene = std::make_shared<const Scene>(loadGltf(path, options));
  } catch (const std::exception& e) {
    // The loader's messages already name the file; others (bad_alloc, ...) get it here.
    const std::string what = e.what();
    r.error = what.find(path) != std::string::npos ? what : path + ": " + what;
  }
  return r;
}

void SceneLoader::start(const std::string& path) {
  if (pending_.valid()) pending_.wait();
  pendingPath_ = path;
  pending_ = std::async(std::launch::async, [path, options = options_] { return load(path, options); });
}

void SceneLoader::start(const std::string& path, const EnvironmentChoice& environment,
                        std::shared_ptr<const EnvironmentDesc> read) {
  if (pending_.valid()) pending_.wait();
  pendingPath_ = path;
  pending_ = std::async(std::launch::async, [path, environment, read = std::move(read), options = options_]() mutable {
    SceneLoadResult r;
    options.lightSelection = environment.lightSelection;
    try {
      options.environment = environmentOf(environment, read);
    } catch (const std::exception& e) {
      // EnvironmentError names the map; others (bad_alloc, ...) get it here. The scene file was
      // not read.
      const std::string what = e.what();
      r.path = path;
      r.error = what.find(environment.spec) != std::string::npos ? what : environment.spec + ": " + what;
      r.environment = environment;
      return r;
    }
    r = load(path, options);
    r.environment = environment;
    r.environmentDesc = options.environment;
    return r;
  });
}

std::optional<SceneLoadResult> SceneLoader::poll() {
  if (!pending_.valid() || pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
  SceneLoadResult r = pending_.get();
  pendingPath_.clear();
  return r;
}

}  // namespace pathlab::ui
