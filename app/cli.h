// The whole command line on one CLI11 App, built the same way by main and by the tests, with the
// checks every option gets whichever subcommand declares it.
#pragma once

#include "app/check_command.h"
#include "app/converge_command.h"
#include "app/finite_numbers.h"
#include "app/inspect_command.h"
#include "app/make_volume_command.h"
#include "app/outliers_command.h"
#include "app/render_command.h"
#include "app/view_command.h"

#include <CLI/CLI.hpp>

namespace pathlab::app {

struct CliOptions {
  RenderOptions render;
  ConvergeOptions converge;
  ViewOptions view;
  CheckCommandOptions check;
  InspectOptions inspect;
  OutliersOptions outliers;
  MakeVolumeOptions makeVolume;
};

// Registers every subcommand on `app`, then requireFiniteNumbers.
void addCommands(CLI::App& app, CliOptions& options);

}  // namespace pathlab::app
