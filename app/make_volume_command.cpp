// `pathlab make-volume`: a procedural density grid written as .vdb.
#include "app/make_volume_command.h"

#include "app/output_check.h"
#include "app/shared_options.h"
#include "core/io/vdb_file.h"
#include "core/media/procedural_volumes.h"

#include <fmt/core.h>

#include <iostream>
#include <stdexcept>

namespace pathlab::app {

namespace {
constexpr int kMaxResolution = 400;  // 64 M voxels: vdb_file.h's kMaxDensityVoxels
}

void addMakeVolumeCommand(CLI::App& app, MakeVolumeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "make-volume",
      "Write a procedural density grid as an OpenVDB file (for PATHLAB_materials_volume_grid): smoke (the bundled "
      "plume), constant or ramp, its voxel centres filling the unit cube [-0.5, 0.5]^3");
  // The kind is checked by runMakeVolume (one line naming it), not by CLI11: every positional is
  // plain text to the command line (tests/cli/numeric_options_test.cpp walks them so).
  cmd->add_option("kind", o.kind, "smoke, constant or ramp")->required();
  cmd->add_option("output", o.output, "The .vdb file to write")->required();
  cmd->add_option("--resolution", o.resolution, fmt::format("Voxels a side (default 64, 2 to {})", kMaxResolution))
      ->check(CLI::Range(2, kMaxResolution));
  cmd->add_option("--value", o.value, "constant: its density; ramp: density at the top face minus the bottom's (default 1)")
      ->check(CLI::Range(0.f, kMaxDensityValue / 2.f));
  cmd->add_option("--seed", o.seed, "smoke: the noise's seed (default 1)");
  cmd->add_option("--grid", o.grid, "The grid's name in the file (default density)");
  addForceFlag(cmd, o.force, "the .vdb if it exists");
}

int runMakeVolume(const MakeVolumeOptions& o) {
  ProceduralVolume kind{};
  if (!parseProceduralVolume(o.kind, kind))
    throw std::runtime_error("make-volume: unknown kind '" + o.kind + "' (smoke, constant or ramp)");
  if (o.grid.empty()) throw std::runtime_error("make-volume --grid: the name must not be empty");
  checkOutputWritable(o.output);
  refuseExisting(o.output, o.force);
  const DensityGrid grid = makeProceduralVolume(kind, o.resolution, o.value, o.seed);
  writeDensityVdb(o.output, o.grid, grid, proceduralVoxelSize(o.resolution), proceduralOrigin(o.resolution));
  std::cout << fmt::format("{}: {} grid '{}', {}^3 voxels of size 1/{}, the unit cube around the origin\n", o.output,
                           o.kind, o.grid, o.resolution, o.resolution);
  return 0;
}

}  // namespace pathlab::app
