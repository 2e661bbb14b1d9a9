// `pathlab make-volume` (issue 35): writes one of pathlab's procedural density grids
// (core/media/procedural_volumes.h) as an OpenVDB file, for PATHLAB_materials_volume_grid. The
// bundled smoke scene's assets/smoke.vdb is `pathlab make-volume smoke assets/smoke.vdb`.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace pathlab::app {

struct MakeVolumeOptions {
  std::string kind;        // smoke, constant, ramp
  std::string output;      // the .vdb
  int resolution = 64;     // voxels a side
  float value = 1.f;       // constant's density, ramp's slope
  uint64_t seed = 1;       // smoke's noise
  std::string grid = "density";
  bool force = false;
};

void addMakeVolumeCommand(CLI::App& app, MakeVolumeOptions& options);
int runMakeVolume(const MakeVolumeOptions& options);

}  // namespace pathlab::app
