// Registration of the options several subcommands share.
#include "app/shared_options.h"

#include "core/camera/image_size.h"

#include <fmt/core.h>

#include <algorithm>
#include <thread>

namespace pathlab::app {

void addSceneArgument(CLI::App* cmd, std::string& scene, const char* defaultNote) {
  const std::string help = "glTF 2.0 scene (.gltf or .glb)";
  if (defaultNote) cmd->add_option("scene", scene, help + "; default: " + defaultNote);
  else cmd->add_option("scene", scene, help)->required();
}

SceneDesc readScene(SceneOptions& scene) {
  finishEnvironmentOptions(scene.environment, scene.load);
  return loadGltf(scene.path, scene.load);
}

void addSampleBudgetOptions(CLI::App* cmd, SampleBudget& b, const SampleBudgetHelp& help) {
  auto* spp = cmd->add_option("--spp", b.spp, help.spp)->check(CLI::Range(help.minSpp, kMaxSpp));
  cmd->add_option("--time", b.seconds, help.time)->check(CLI::Range(0.001, 7.0 * 24 * 3600))->excludes(spp);
}

Vec2i ImageSizeOptions::sizeFor(std::optional<float> aspect, int longestSide) const {
  return imageSizeForAspect(aspect, width > 0 ? std::optional(width) : std::nullopt,
                            height > 0 ? std::optional(height) : std::nullopt, longestSide);
}

void addImageSizeOptions(CLI::App* cmd, ImageSizeOptions& size, const ImageSizeHelp& help) {
  const std::string defaults =
      fmt::format("(default: {}the camera's shape, longest side {})", help.otherwise, help.longestSide);
  cmd->add_option("--width", size.width, "Image width in pixels " + defaults)->check(CLI::Range(1, help.maxSide));
  cmd->add_option("--height", size.height, "Image height in pixels " + defaults)->check(CLI::Range(1, help.maxSide));
}

void addThreadsOption(CLI::App* cmd, int& threads, const char* what) {
  cmd->add_option("--threads", threads, fmt::format("{} threads (0: all hardware threads)", what))
      ->check(CLI::Range(0, 1024));
}

ThreadLimit::ThreadLimit(int threads)
    : threads_(threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))),
      control_(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads_)) {}

void addLoadOptions(CLI::App* cmd, LoadOptions& load, EnvironmentOptions& environment) {
  cmd->add_option("--max-triangles", load.maxTriangles, "Refuse scenes that instance more triangles than this")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  addEnvironmentOptions(cmd, environment);
}

void addForceFlag(CLI::App* cmd, bool& force, const std::string& what) {
  cmd->add_flag("-f,--force", force, "Overwrite " + what);
}

}  // namespace pathlab::app
