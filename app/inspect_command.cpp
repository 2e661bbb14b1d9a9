// `pathlab inspect`: the options, one sample replayed, its text and its JSON file.
#include "app/inspect_command.h"

#include "app/output_check.h"
#include "core/camera/image_size.h"
#include "core/io/text_file.h"
#include "core/render/inspection_report.h"
#include "core/render/render_session.h"

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace pathlab::app {

namespace {

// As render's --spp: a pass index beyond it is no sample a render of pathlab ever takes.
constexpr uint64_t kMaxSample = kMaxSpp - 1;
// Under variance-aware MIS, inspecting sample N renders the N passes before it (their factors).
constexpr uint64_t kMaxVarianceAwareReplay = 4096;
// A chain's state after --pass N is found by rendering N passes (a mutation a pixel each): a bound
// that keeps the wait to minutes at the default size.
constexpr uint64_t kMaxChainPasses = 4096;

}  // namespace

void addInspectCommand(CLI::App& app, InspectOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "inspect", "Replay one sample of one pixel: every (s,t) technique, its path and the path's density and MIS "
                 "weight under every technique of its length (text, and JSON with --json); for mlt, one chain's "
                 "state: its primary numbers, technique and path");
  addSceneArgument(cmd, o.scene.path);
  cmd->add_option("--pixel", o.pixel, "The pixel X,Y (from the top left); every integrator but mlt");
  cmd->add_option("--sample", o.sample, "The sample (pass) index, 0 .. 16777215 (default 0)");
  cmd->add_option("--chain", o.chain,
                  "With --integrator mlt: the Metropolis chain whose state to show (its primary numbers, "
                  "technique and path), 0 .. chains - 1");
  cmd->add_option("--pass", o.pass,
                  fmt::format("With --chain: the state after this many passes, 0 .. {} (default 0: where the "
                              "chain starts, resampled from the bootstrap)",
                              kMaxChainPasses));
  cmd->add_option("--json", o.json, "Also write the inspection as JSON to this file");
  addImageSizeOptions(cmd, o.size, {kMaxImageSide, kDefaultLongestSide});
  addEstimatorOptions(cmd, o.estimator);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
  addForceFlag(cmd, o.force, "the JSON file if it exists");
}

std::unique_ptr<Scene> loadSceneToInspect(SceneOptions& sceneOptions, const ImageSizeOptions& sizeOptions,
                                          RenderSettings& settings, const std::string& json, bool force) {
  if (!json.empty()) {
    checkOutputWritable(json);
    refuseExisting(json, force);
  }
  auto scene = std::make_unique<Scene>(readScene(sceneOptions));
  for (const std::string& w : scene->warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  const Vec2i size = sizeOptions.sizeFor(cameraAspect(settings.camera, scene->cameraDesc()), kDefaultLongestSide);
  settings.width = size.x;
  settings.height = size.y;
  return scene;
}

int runInspect(InspectOptions o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt)
    throw std::invalid_argument("inspect replays one bidirectional sample: use --integrator bpt, lt or mlt");
  const bool metropolis = settings.integrator == IntegratorKind::Mlt;
  if (metropolis) {
    // A Metropolis render's samples are its chains' states, not a pixel's independent samples.
    if (!o.pixel.empty() || o.sample)
      throw std::invalid_argument("--integrator mlt: a Metropolis render's samples are its chains' states, not a "
                                  "pixel's: give --chain C [--pass N] instead of --pixel and --sample");
    if (!o.chain) throw std::invalid_argument("--integrator mlt: give the chain to inspect, --chain C [--pass N]");
    if (o.pass && *o.pass > kMaxChainPasses)
      throw std::invalid_argument(fmt::format("--pass {} is more than {} passes", *o.pass, kMaxChainPasses));
  } else if (o.chain || o.pass) {
    throw std::invalid_argument("--chain and --pass inspect a Metropolis chain: use them with --integrator mlt");
  } else if (o.pixel.empty()) {
    throw std::invalid_argument("give the pixel to inspect, --pixel X,Y");
  }
  long long x = -1, y = -1;
  char extra = 0;
  if (!metropolis && std::sscanf(o.pixel.c_str(), "%lld,%lld%c", &x, &y, &extra) != 2)
    throw std::invalid_argument(fmt::format("--pixel: '{}' is not X,Y", o.pixel));
  const uint64_t sample = o.sample.value_or(0);
  if (sample > kMaxSample)
    throw std::invalid_argument(fmt::format("--sample {} is past the last sample index {}", sample, kMaxSample));
  const std::unique_ptr<Scene> loaded = loadSceneToInspect(o.scene, o.size, settings, o.json, o.force);
  const Scene& scene = *loaded;
  if (!metropolis && (x < 0 || y < 0 || x >= settings.width || y >= settings.height))
    throw std::invalid_argument(
        fmt::format("--pixel {},{} is outside the {} x {} image", x, y, settings.width, settings.height));
  validateSettingsForScene(settings, scene);
  RenderSession session(scene, settings);
  if (!metropolis && (settings.mis.heuristic == MisHeuristic::VarianceAware || settings.lightPathsAuto ||
                     settings.mis.heuristic == MisHeuristic::Optimal)) {
    // Pass N was weighed with the factors (or rendered at the light subpath count, or corrected
    // with the coefficients) that passes 0 .. N-1 chose: render them first, so the replay weighs as
    // the render did.
    if (sample > kMaxVarianceAwareReplay)
      throw std::invalid_argument(fmt::format("--sample {} under {} would render the {} passes before it to find "
                                              "what they chose: at most {}",
                                              sample,
                                              settings.lightPathsAuto ? "--light-paths auto"
                                              : settings.mis.heuristic == MisHeuristic::Optimal
                                                  ? "--mis optimal"
                                                  : "--mis variance-aware",
                                              sample, kMaxVarianceAwareReplay));
    for (uint64_t p = 0; p < sample; ++p) session.renderPass();
  }
  const SampleInspection inspection =
      metropolis ? inspectChain(session, *o.chain, o.pass.value_or(0))
                 : inspectSample(session, static_cast<int>(x), static_cast<int>(y), sample);
  printInspection(std::cout, settings, inspection, true);
  if (!o.json.empty()) {
    writeTextAtomically(o.json, inspectionJson(settings, inspection).dump(2) + "\n");
    std::cerr << "wrote " << o.json << "\n";
  }
  return 0;
}

}  // namespace pathlab::app
