// Scene cache of the benchmarks.
#include "tests/bench/bench_scenes.h"

#include "core/scene/gltf_loader.h"

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <thread>

namespace pathlab::bench {

std::vector<std::string> bundledScenes() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(PATHLAB_ASSETS_DIR))
    if (entry.path().extension() == ".gltf") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

const Scene& benchScene(const std::string& name) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<Scene>> scenes;
  std::lock_guard lock(mutex);
  auto& scene = scenes[name];
  if (!scene) scene = std::make_unique<Scene>(loadGltf(std::string(PATHLAB_ASSETS_DIR) + "/" + name + ".gltf"));
  return *scene;
}

int allThreads() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

namespace {
std::atomic<bool> failed{false};
}  // namespace

void failBenchmark(benchmark::State& state, const std::string& message) {
  failed = true;
  state.SkipWithError(message.c_str());
}

bool anyBenchmarkFailed() { return failed; }

}  // namespace pathlab::bench
