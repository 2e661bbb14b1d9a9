// `pathlab check`: render with the check's sums attached, then print one line per technique and
// a verdict (core/check/check_report.h).
#include "app/check_command.h"

#include "app/progress.h"
#include "core/camera/image_size.h"
#include "core/render/render_session.h"

#include <fmt/core.h>
#include <tbb/global_control.h>

#include <chrono>
#include <iostream>
#include <thread>

namespace pathlab::app {

namespace {
constexpr double kDefaultCheckSeconds = 10.0;
constexpr int kDefaultCheckSide = 128;
constexpr int kMaxCheckSide = 4096;
}  // namespace

void addCheckCommand(CLI::App& app, CheckCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "check", "Check that every enabled (s,t) technique agrees with the others on the paths both can sample; exit 1 "
               "when one disagrees");
  cmd->add_option("scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  auto* spp = cmd->add_option("--spp", o.spp, "Passes (samples per pixel) to compare over")->check(CLI::Range(2, 1 << 24));
  cmd->add_option("--time", o.seconds, "Render for this many seconds (default 10)")
      ->check(CLI::Range(0.001, 7.0 * 24 * 3600))
      ->excludes(spp);
  cmd->add_option("--width", o.width, "Image width (default: the camera's shape, longest side 128)")
      ->check(CLI::Range(1, kMaxCheckSide));
  cmd->add_option("--height", o.height, "Image height (default: the camera's shape, longest side 128)")
      ->check(CLI::Range(1, kMaxCheckSide));
  addEstimatorOptions(cmd, o.estimator);
  cmd->add_option("--blocks", o.estimator.settings.checkBlocks,
                  "Compare over a BLOCKS x BLOCKS grid of image blocks as well as the whole image (default 4)")
      ->check(CLI::Range(1, kMaxCheckBlocks));
  cmd->add_option("--alpha", o.check.alpha, "Family-wise false-alarm rate of the whole check (default 0.01)")
      ->check(CLI::Range(1e-12, 0.5));
  cmd->add_option("--min-hits", o.check.minNonzeroPasses,
                  "Compare a pair in a region only when both found paths there in at least this many passes (default 20)")
      ->check(CLI::Range(uint64_t{2}, uint64_t{1} << 40));
  cmd->add_option("--threads", o.threads, "Worker threads (0: all hardware threads)")->check(CLI::Range(0, 1024));
  cmd->add_option("--max-triangles", o.load.maxTriangles, "Refuse scenes that instance more triangles than this")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  addEnvironmentOptions(cmd, o.environment);
}

int runCheck(CheckCommandOptions o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt)
    throw std::invalid_argument("check compares the bidirectional techniques: use --integrator bpt or lt");
  const int threads = o.threads > 0 ? o.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  tbb::global_control threadLimit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));

  finishEnvironmentOptions(o.environment, o.load);
  Scene scene(loadGltf(o.scene, o.load));
  // The camera's shape, as `render` (core/camera/image_size.h).
  const Vec2i size = imageSizeForAspect(cameraAspect(settings.camera, scene.cameraDesc()),
                                        o.width > 0 ? std::optional(o.width) : std::nullopt,
                                        o.height > 0 ? std::optional(o.height) : std::nullopt, kDefaultCheckSide);
  settings.width = size.x;
  settings.height = size.y;
  for (const std::string& w : scene.warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  if (const std::string w = misOffWarning(scene, settings); !w.empty()) std::cerr << "pathlab: warning: " << w << "\n";
  if (const std::string w = biasInjectionWarning(settings); !w.empty()) std::cerr << "pathlab: warning: " << w << "\n";

  RenderSession session(scene, settings);
  const bool timed = o.spp == 0;
  const double seconds = o.seconds > 0.0 ? o.seconds : kDefaultCheckSeconds;
  const uint64_t targetPasses = static_cast<uint64_t>(o.spp);
  const uint64_t minPasses = std::max<uint64_t>(o.check.minPasses, 2);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  {
    const double pixels = static_cast<double>(session.film().pixelCount());
    ProgressBar bar([&] {
      const double passFraction = static_cast<double>(session.pixelsDoneInPass()) / pixels;
      const double done = timed ? elapsed() / seconds
                                : (static_cast<double>(session.passes()) + passFraction) / static_cast<double>(targetPasses);
      return std::pair{done, fmt::format("{} passes  {:.1f} s", session.passes(), elapsed())};
    });
    // A timed check still runs the passes a standard error needs.
    while (timed ? (session.passes() < minPasses || elapsed() < seconds) : session.passes() < targetPasses)
      session.renderPass();
  }
  const CheckReport report = checkReport(*session.techniqueCheck(), o.check);
  std::cout << fmt::format("{}: {}, {} x {}, seed {}\n", o.scene, integratorName(settings.integrator), settings.width,
                           settings.height, settings.seed);
  std::cout << checkReportText(report);
  return report.agrees() ? 0 : 1;
}

}  // namespace pathlab::app
