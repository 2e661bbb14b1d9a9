// The options that light a scene, shared by render, view, converge, check and inspect: --environment
// FILE.exr|FILE.hdr|R,G,B, --environment-strength, --environment-rotation, --no-default-light, and
// --light-sampler (how next-event estimation chooses among the lights).
#pragma once

#include "core/scene/gltf_loader.h"

#include <CLI/CLI.hpp>

#include <string>

namespace pathlab::app {

struct EnvironmentOptions {
  std::string spec;  // empty: none
  float strength = 1.f;
  float rotationDegrees = 0.f;
  bool noDefaultLight = false;
  std::string lightSampler = "auto";  // auto | power | bvh
};

void addEnvironmentOptions(CLI::App* cmd, EnvironmentOptions& options);
// Reads the environment into load.environment and sets load.defaultLight and load.lightSelection;
// throws one line naming
// the file and the problem (EnvironmentError).
void finishEnvironmentOptions(const EnvironmentOptions& options, LoadOptions& load);
// What of `load` lights the scene, as text for a reference image's cache key: empty without an
// environment, else its size, strength, rotation and an FNV-1a hash of its radiance.
std::string environmentKeyText(const LoadOptions& load);

}  // namespace pathlab::app
