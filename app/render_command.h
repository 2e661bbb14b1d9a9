// `pathlab render`: options, validation and the headless render loop.
#pragma once

#include "app/estimator_options.h"
#include "app/shared_options.h"

#include <CLI/CLI.hpp>

#include <string>

namespace pathlab::app {

class Job;

struct RenderOptions {
  SceneOptions scene;
  std::string output;
  EstimatorOptions estimator;
  // Neither side given: the camera's aspect with the longest side 512.
  ImageSizeOptions size;
  SampleBudget budget;  // neither given: 64 spp
  int threads = 0;      // 0: every hardware thread
  float exposure = 0.f;
  bool force = false;
  bool stats = false;   // print the per-technique counters
  std::string replay;   // "X,Y,SAMPLE": print that one sample's techniques instead of rendering
  int techniqueMaps = 0;  // > 0: also write the technique maps up to this length
  int varianceMaps = 0;   // > 0: also write the variance maps up to this length
  bool chainDensity = false;  // mlt: also write where the chains spent their time
  int mutationsPerPixel = 0;  // --integrator mlt: the budget in mutations per pixel (0: --spp / --time)
};

void addRenderCommand(CLI::App& app, RenderOptions& options);
// The options of render that decide the estimate, registered on `cmd` (render's, and the Python
// module's Settings, which parses its keyword arguments with them): the image size, the estimator
// options, --pyramid, --technique-maps, --threads and --check-mis.
void addRenderEstimateOptions(CLI::App* cmd, RenderOptions& options);
// After parsing, before the scene: the estimator options into settings (finishEstimatorOptions)
// and the technique maps' pyramid; throws the one-line messages render prints.
void finishRenderEstimate(RenderOptions& options);
// Refuses --width x --height beyond the pixel limit when both are given (before the scene).
void checkRequestedPixels(const RenderOptions& options);
// The image's size on `scene`'s camera (--width / --height, else the camera's shape), into the
// settings; throws when it has too many pixels.
void sizeRenderForScene(RenderOptions& options, const CameraDesc& camera);
// Returns the process exit code. Errors are exceptions, reported by main. As one rank of `job`
// (app/job.h; one process: a plain Job): its share of the passes; the leader writes the outputs.
int runRender(RenderOptions options, Job& job);

}  // namespace pathlab::app
