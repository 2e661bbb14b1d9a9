#include "app/inspect_command.h"

#include "app/output_check.h"
#include "ui/inspection_report.h"
#include "core/camera/image_size.h"
#include "core/render/render_session.h"

#include <fmt/core.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <stdexcept>

namespace pathlab::app {

namespace {

// As render's --spp: a pass index beyond it is no sample a render of pathlab ever takes.
constexpr uint64_t kMaxSample = (1u << 24) - 1;

}  // namespace

void addInspectCommand(CLI::App& app, InspectOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "inspect", "Replay one sample of one pixel: every (s,t) technique, its path and the path's density and MIS "
                 "weight under every technique of its length (text, and JSON with --json)");
  cmd->add_option("scene", o.scene, "glTF 2.0 scene (.gltf or .glb)")->required();
  cmd->add_option("--pixel", o.pixel, "The pixel X,Y (from the top left)")->required();
  cmd->add_option("--sample", o.sample, "The sample (pass) index, 0 .. 16777215 (default 0)");
  cmd->add_option("--json", o.json, "Also write the inspection as JSON to this file");
  cmd->add_option("--width", o.width, "Image width (default: the camera's shape, longest side 512)")
      ->check(CLI::Range(1, 16384));
  cmd->add_option("--height", o.height, "Image height (default: the camera's shape, longest side 512)")
      ->check(CLI::Range(1, 16384));
  addEstimatorOptions(cmd, o.estimator);
  addEnvironmentOptions(cmd, o.environment);
  cmd->add_option("--max-triangles", o.load.maxTriangles, "Refuse scenes that instance more triangles than this")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  cmd->add_flag("-f,--force", o.force, "Overwrite the JSON file if it exists");
}

int runInspect(InspectOptions o) {
  finishEstimatorOptions(o.estimator);
  RenderSettings& settings = o.estimator.settings;
  if (settings.integrator == IntegratorKind::Pt)
    throw std::invalid_argument("inspect shows the bidirectional techniques: use --integrator bpt or lt");
  long long x = -1, y = -1;
  char extra = 0;
  if (std::sscanf(o.pixel.c_str(), "%lld,%lld%c", &x, &y, &extra) != 2)
    throw std::invalid_argument(fmt::format("--pixel: '{}' is not X,Y", o.pixel));
  if (o.sample > kMaxSample)
    throw std::invalid_argument(fmt::format("--sample {} is past the last sample index {}", o.sample, kMaxSample));
  if (!o.json.empty()) {
    checkOutputWritable(o.json);
    if (!o.force && std::filesystem::exists(o.json))
      throw std::runtime_error(o.json + ": file exists (pass --force to overwrite it)");
  }
  finishEnvironmentOptions(o.environment, o.load);
  Scene scene(loadGltf(o.scene, o.load));
  for (const std::string& w : scene.warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  const Vec2i size = imageSizeForAspect(cameraAspect(settings.camera, scene.cameraDesc()),
                                        o.width > 0 ? std::optional(o.width) : std::nullopt,
                                        o.height > 0 ? std::optional(o.height) : std::nullopt);
  settings.width = size.x;
  settings.height = size.y;
  if (x < 0 || y < 0 || x >= settings.width || y >= settings.height)
    throw std::invalid_argument(
        fmt::format("--pixel {},{} is outside the {} x {} image", x, y, settings.width, settings.height));
  RenderSession session(scene, settings);
  const SampleInspection inspection = inspectSample(session, static_cast<int>(x), static_cast<int>(y), o.sample);
  ui::printInspection(std::cout, settings, inspection, true);
  if (!o.json.empty()) {
    writeTextAtomically(o.json, ui::inspectionJson(settings, inspection).dump(2) + "\n");
    std::cerr << "wrote " << o.json << "\n";
  }
  return 0;
}

}  // namespace pathlab::app
