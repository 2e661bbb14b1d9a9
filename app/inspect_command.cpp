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

}  // namespace

void addInspectCommand(CLI::App& app, InspectOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "inspect", "Replay one sample of one pixel: every (s,t) technique, its path and the path's density and MIS "
                 "weight under every technique of its length (text, and JSON with --json)");
  addSceneArgument(cmd, o.scene.path);
  cmd->add_option("--pixel", o.pixel, "The pixel X,Y (from the top left)")->required();
  cmd->add_option("--sample", o.sample, "The sample (pass) index, 0 .. 16777215 (default 0)");
  cmd->add_option("--json", o.json, "Also write the inspection as JSON to this file");
  addImageSizeOptions(cmd, o.size, {kMaxImageSide, kDefaultLongestSide});
  addEstimatorOptions(cmd, o.estimator);
  addLoadOptions(cmd, o.scene.load, o.scene.environment);
  addForceFlag(cmd, o.force, "the JSON file if it exists");
}

int runInspect(InspectOptions o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt || settings.integrator == IntegratorKind::Mlt)
    throw std::invalid_argument("inspect replays one independent bidirectional sample: use --integrator bpt or lt");
  long long x = -1, y = -1;
  char extra = 0;
  if (std::sscanf(o.pixel.c_str(), "%lld,%lld%c", &x, &y, &extra) != 2)
    throw std::invalid_argument(fmt::format("--pixel: '{}' is not X,Y", o.pixel));
  if (o.sample > kMaxSample)
    throw std::invalid_argument(fmt::format("--sample {} is past the last sample index {}", o.sample, kMaxSample));
  if (!o.json.empty()) {
    checkOutputWritable(o.json);
    refuseExisting(o.json, o.force);
  }
  Scene scene(readScene(o.scene));
  for (const std::string& w : scene.warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  const Vec2i size = o.size.sizeFor(cameraAspect(settings.camera, scene.cameraDesc()), kDefaultLongestSide);
  settings.width = size.x;
  settings.height = size.y;
  if (x < 0 || y < 0 || x >= settings.width || y >= settings.height)
    throw std::invalid_argument(
        fmt::format("--pixel {},{} is outside the {} x {} image", x, y, settings.width, settings.height));
  RenderSession session(scene, settings);
  const SampleInspection inspection = inspectSample(session, static_cast<int>(x), static_cast<int>(y), o.sample);
  printInspection(std::cout, settings, inspection, true);
  if (!o.json.empty()) {
    writeTextAtomically(o.json, inspectionJson(settings, inspection).dump(2) + "\n");
    std::cerr << "wrote " << o.json << "\n";
  }
  return 0;
}

}  // namespace pathlab::app
