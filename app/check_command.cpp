// `pathlab check`: render with the check's sums attached, then print one line per technique and
// a verdict (core/check/check_report.h).
#include "app/check_command.h"

#include "app/progress.h"
#include "app/shared_options.h"
#include "core/camera/image_size.h"
#include "core/render/render_session.h"

#include <fmt/core.h>

#include <chrono>
#include <iostream>

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
  addSceneArgument(cmd, o.scene.path);
  addSampleBudgetOptions(cmd, o.budget,
                         {2, "Passes (samples per pixel) to compare over", "Render for this many seconds (default 10)"});
  addImageSizeOptions(cmd, o.size, {kMaxCheckSide, kDefaultCheckSide});
  addEstimatorOptions(cmd, o.estimator);
  cmd->add_option("--blocks", o.estimator.settings.checkBlocks,
                  "Compare over a BLOCKS x BLOCKS grid of image blocks as well as the whole image (default 4)")
      ->check(CLI::Range(1, kMaxCheckBlocks));
  cmd->add_option("--alpha", o.check.alpha, "Family-wise false-alarm rate of the whole check (default 0.01)")
      ->check(CLI::Range(1e-12, 0.5));
  cmd->add_option("--min-hits", o.check.minNonzeroPasses,
                  "Compare a pair in a region only when both found paths there in at least this many passes (default 20)")
      ->check(CLI::Range(uint64_t{2}, uint64_t{1} << 40));
  addThreadsOption(cmd, o.threads);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
}

int runCheck(CheckCommandOptions o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt)
    throw std::invalid_argument("check compares the bidirectional techniques: use --integrator bpt or lt");
  const ThreadLimit threadLimit(o.threads);

  Scene scene(readScene(o.scene));
  // The camera's shape, as `render` (core/camera/image_size.h).
  const Vec2i size = o.size.sizeFor(cameraAspect(settings.camera, scene.cameraDesc()), kDefaultCheckSide);
  settings.width = size.x;
  settings.height = size.y;
  printWarnings(std::cerr, scene, settings);

  RenderSession session(scene, settings);
  const bool timed = o.budget.spp == 0;
  const double seconds = o.budget.seconds > 0.0 ? o.budget.seconds : kDefaultCheckSeconds;
  const uint64_t targetPasses = static_cast<uint64_t>(o.budget.spp);
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
  std::cout << fmt::format("{}: {}, {} x {}, seed {}\n", o.scene.path, integratorName(settings.integrator), settings.width,
                           settings.height, settings.seed);
  std::cout << checkReportText(report);
  return report.agrees() ? 0 : 1;
}

}  // namespace pathlab::app
