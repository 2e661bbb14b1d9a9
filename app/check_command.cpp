// `pathlab check`: render with the check's sums attached, then print one line per technique and
// a verdict (core/check/check_report.h).
#include "app/check_command.h"

#include "app/output_check.h"
#include "app/progress.h"
#include "app/shared_options.h"
#include "core/camera/image_size.h"
#include "core/check/check_json.h"
#include "core/check/merge_bias.h"
#include "core/io/text_file.h"
#include "core/render/render_session.h"

#include <fmt/core.h>

#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <vector>

namespace pathlab::app {

namespace {
constexpr double kDefaultCheckSeconds = 10.0;
constexpr int kDefaultCheckSide = 128;
constexpr int kMaxCheckSide = 4096;
constexpr int kMaxRadiusLevels = 6;
}  // namespace

void addCheckCommand(CLI::App& app, CheckCommandOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "check", "Check that every enabled (s,t) technique agrees with the others on the paths both can sample; exit 1 "
               "when one disagrees");
  addSceneArgument(cmd, o.scene.path);
  addCheckOptions(cmd, o);
  cmd->add_option("--json", o.json, "Also write the verdict (and each merge's bias radius by radius) as JSON to this file");
  addForceFlag(cmd, o.force, "the --json file");
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
}

void addCheckOptions(CLI::App* cmd, CheckCommandOptions& o) {
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
  cmd->add_option("--radius-levels", o.radiusLevels,
                  "With merging techniques: render at this many radii, --radius halved each time (alpha = 1), and "
                  "judge each merge by its difference from the connections extrapolated to r -> 0 (default 3)")
      ->check(CLI::Range(2, kMaxRadiusLevels));
  addThreadsOption(cmd, o.threads);
}

void finishCheckOptions(CheckCommandOptions& o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt)
    throw std::invalid_argument("check compares the bidirectional techniques: use --integrator bpt or lt");
  const bool merges = covers(enabledTechniques(settings).families(), TechniqueKind::Merge);
  if (merges && settings.mergeRadiusAlpha != 1.f)
    throw std::invalid_argument(fmt::format("--radius-alpha {:g}: check renders each radius fixed, so that its bias is "
                                            "that of one radius (alpha 1)",
                                            settings.mergeRadiusAlpha));
}

CheckOutcome checkScene(CheckCommandOptions& o, const Scene& scene, bool progress, const std::atomic<bool>* stop) {
  RenderSettings& settings = o.estimator.settings;
  const bool merges = covers(enabledTechniques(settings).families(), TechniqueKind::Merge);
  // The camera's shape, as `render` (core/camera/image_size.h).
  const Vec2i size = o.size.sizeFor(cameraAspect(settings.camera, scene.cameraDesc()), kDefaultCheckSide);
  settings.width = size.x;
  settings.height = size.y;

  // One render per radius, each with its own seed so the radii's differences are independent
  // (merge_bias.h); without merges, the one render of the connections' check.
  const int levels = merges ? o.radiusLevels : 1;
  const bool timed = o.budget.spp == 0;
  const double seconds = (o.budget.seconds > 0.0 ? o.budget.seconds : kDefaultCheckSeconds) / levels;
  const uint64_t targetPasses = static_cast<uint64_t>(o.budget.spp);
  const uint64_t minPasses = std::max<uint64_t>(o.check.minPasses, 2);
  std::vector<std::unique_ptr<RenderSession>> sessions;
  std::vector<MergeBiasLevel> radii;
  for (int level = 0; level < levels; ++level) {
    RenderSettings s = settings;
    s.mergeRadius = firstMergeRadius(settings) / static_cast<float>(1 << level);
    s.seed = settings.seed + static_cast<uint64_t>(level);
    sessions.push_back(std::make_unique<RenderSession>(scene, s));
    RenderSession& session = *sessions.back();
    const auto start = std::chrono::steady_clock::now();
    auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
    const double pixels = static_cast<double>(session.film().pixelCount());
    const std::string label = merges ? fmt::format("r = {:g}  ", *s.mergeRadius) : "";
    std::optional<ProgressBar> bar;
    if (progress)
      bar.emplace([&] {
        const double passFraction = static_cast<double>(session.pixelsDoneInPass()) / pixels;
        const double done = timed ? elapsed() / seconds
                                  : (static_cast<double>(session.passes()) + passFraction) / static_cast<double>(targetPasses);
        return std::pair{done, fmt::format("{}{} passes  {:.1f} s", label, session.passes(), elapsed())};
      });
    // A timed check still runs the passes a standard error needs.
    while (timed ? (session.passes() < minPasses || elapsed() < seconds) : session.passes() < targetPasses) {
      session.renderPass();
      if (stop && stop->load(std::memory_order_relaxed)) throw CheckStopped();
    }
    radii.push_back(MergeBiasLevel{*s.mergeRadius, session.techniqueCheck()});
  }
  // The connections do not depend on the radius: their sums over every render are one longer check.
  TechniqueCheck pooled = *sessions.front()->techniqueCheck();
  for (size_t l = 1; l < sessions.size(); ++l) pooled.absorb(*sessions[l]->techniqueCheck());
  // The connections' verdicts; a merge is judged by its bias against the radius instead.
  CheckOutcome outcome{settings, levels, checkReport(pooled, o.check), std::nullopt};
  if (merges) outcome.merges = mergeBiasReport(radii, o.check);
  return outcome;
}

nlohmann::json checkOutcomeJson(const CheckOutcome& outcome, const std::string& scenePath) {
  nlohmann::json json = checkJson(outcome.report, outcome.merges ? &*outcome.merges : nullptr);
  json["scene"] = scenePath;
  json["integrator"] = integratorName(outcome.settings.integrator);
  json["width"] = outcome.settings.width;
  json["height"] = outcome.settings.height;
  json["seed"] = outcome.settings.seed;
  return json;
}

int runCheck(CheckCommandOptions o) {
  finishCheckOptions(o);
  if (!o.json.empty()) {
    checkOutputWritable(o.json);
    refuseExisting(o.json, o.force);
  }
  const ThreadLimit threadLimit(o.threads);
  Scene scene(readScene(o.scene));
  printWarnings(std::cerr, scene, o.estimator.settings);
  const CheckOutcome outcome = checkScene(o, scene, true);
  const RenderSettings& settings = outcome.settings;
  std::cout << fmt::format("{}: {}, {} x {}, seed {}{}\n", o.scene.path, integratorName(settings.integrator),
                           settings.width, settings.height, settings.seed,
                           outcome.merges ? fmt::format(", merges at {} radii from {:g} (the i-th: halved i times, seed + i)",
                                                        outcome.radiusLevels, firstMergeRadius(settings))
                                          : "");
  std::cout << checkReportText(outcome.report);
  if (outcome.merges) std::cout << "\n" << mergeBiasText(*outcome.merges);
  if (!o.json.empty()) {
    writeTextAtomically(o.json, checkOutcomeJson(outcome, o.scene.path).dump(2) + "\n");
    std::cerr << "wrote " << o.json << "\n";
  }
  return outcome.agrees() ? 0 : 1;
}

}  // namespace pathlab::app
