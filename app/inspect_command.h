// `pathlab inspect`: one camera sample of one pixel, every (s,t) technique it tried, each full
// path with its vertex densities and the path under every technique of its length, as text and
// JSON (issue 12, "On the command line"; core/render/inspection_report.h).
#pragma once

#include "app/estimator_options.h"
#include "app/shared_options.h"
#include "core/scene/scene.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace pathlab::app {

struct InspectOptions {
  SceneOptions scene;
  EstimatorOptions estimator;
  ImageSizeOptions size;      // as render: the camera's shape, longest side 512, unless given
  std::string pixel;               // "X,Y"
  std::optional<uint64_t> sample;  // the pass index: samples are keyed by (seed, pixel, pass); default 0
  // A Metropolis render (--integrator mlt): its samples are its chains' states.
  std::optional<uint64_t> chain;  // which chain
  std::optional<uint64_t> pass;   // after how many passes (default 0: where it starts)
  std::string json;           // write the inspection here as JSON
  bool force = false;
};

void addInspectCommand(CLI::App& app, InspectOptions& options);

// What `inspect` and `outliers` do before rendering: the JSON output checked (writable, never over
// a file without `force`), the scene loaded with its warnings printed, and `settings` sized to the
// camera's shape (longest side 512 unless given).
std::unique_ptr<Scene> loadSceneToInspect(SceneOptions& scene, const ImageSizeOptions& size,
                                          RenderSettings& settings, const std::string& json, bool force);
int runInspect(InspectOptions options);

}  // namespace pathlab::app
