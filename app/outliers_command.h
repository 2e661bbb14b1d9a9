// `pathlab outliers` (issue 34, "where the noise comes from"): renders and keeps the N weighted
// contributions of highest luminance (the fireflies), each replayed: its pixel, sample and
// technique, its path, the path's density under every technique of its length, and the ratio of
// the density that sampled it to the best density among the enabled techniques ("sampled with
// low probability" as a number). Text, and JSON with --json.
#pragma once

#include "app/estimator_options.h"
#include "app/shared_options.h"

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace pathlab::app {

struct OutliersOptions {
  SceneOptions scene;
  EstimatorOptions estimator;
  ImageSizeOptions size;  // as inspect: the camera's shape, longest side 512, unless given
  uint64_t spp = 16;      // passes rendered
  int top = 10;           // contributions kept
  std::string json;
  int threads = 0;
  bool force = false;
};

void addOutliersCommand(CLI::App& app, OutliersOptions& options);
int runOutliers(OutliersOptions options);

}  // namespace pathlab::app
