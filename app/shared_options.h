// The options several subcommands share, each registered here once: the scene argument, the
// sample budget (--spp / --time), the image size (--width / --height), --threads, what loading a
// scene may do (--max-triangles and the environment options) and --force. Where the commands
// differ on purpose (the fewest samples a check can use, a default size, what --force overwrites),
// the difference is a parameter; the estimator options are app/estimator_options.h.
#pragma once

#include "app/environment_options.h"
#include "core/math/types.h"
#include "core/scene/gltf_loader.h"

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <optional>
#include <string>

namespace pathlab::app {

// The most samples per pixel any command renders (--spp), and so the last sample index + 1.
constexpr int kMaxSpp = 1 << 24;
// The longest --width or --height of an image (check allows less: it needs passes, not pixels).
constexpr int kMaxImageSide = 16384;

// The scene a command renders and how it loads (view keeps these in ui::ViewerOptions).
struct SceneOptions {
  std::string path;
  LoadOptions load;
  EnvironmentOptions environment;  // into `load` by readScene
};
// The positional SCENE. With `defaultNote` (view: the bundled scene) it may be left out.
void addSceneArgument(CLI::App* cmd, std::string& scene, const char* defaultNote = nullptr);
// Reads the environment into scene.load (finishEnvironmentOptions), then the glTF file.
SceneDesc readScene(SceneOptions& scene);

// --spp N or --time SECONDS (one excludes the other); 0: not given.
struct SampleBudget {
  int spp = 0;
  double seconds = 0.0;
};
struct SampleBudgetHelp {
  int minSpp = 1;  // 2 where a standard error is estimated over passes (check, converge)
  const char* spp;
  const char* time;
};
void addSampleBudgetOptions(CLI::App* cmd, SampleBudget& budget, const SampleBudgetHelp& help);

// --width / --height of the image in pixels; 0: not given. Neither given: the camera's shape with
// the longest side the command's default; one given: the other follows the camera's aspect.
struct ImageSizeOptions {
  int width = 0, height = 0;
  // core/camera/image_size.h with the sides given.
  Vec2i sizeFor(std::optional<float> aspect, int longestSide) const;
};
struct ImageSizeHelp {
  int maxSide;
  int longestSide;              // the default, as the command passes it to sizeFor
  const char* otherwise = "";  // a default before the camera's shape (converge: "the reference's, or ")
};
void addImageSizeOptions(CLI::App* cmd, ImageSizeOptions& size, const ImageSizeHelp& help);

// --threads N, 0: every hardware thread. `what` names them in the help ("Worker", "Render").
void addThreadsOption(CLI::App* cmd, int& threads, const char* what = "Worker");
// TBB runs on at most --threads threads while this lives.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads);
  int threads() const { return threads_; }

 private:
  int threads_;
  tbb::global_control control_;
};

// --max-triangles, then the environment options (app/environment_options.h): how a scene loads.
void addLoadOptions(CLI::App* cmd, LoadOptions& load, EnvironmentOptions& environment);

// -f,--force: "Overwrite " + `what`.
void addForceFlag(CLI::App* cmd, bool& force, const std::string& what);

}  // namespace pathlab::app
