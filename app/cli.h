// The whole command line on one CLI11 App, built the same way by main and by the tests, with the
// checks every option gets whichever subcommand declares it.
#pragma once

#include "app/check_command.h"
#include "app/converge_command.h"
#include "app/inspect_command.h"
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
};

// Registers every subcommand on `app`, then requireFiniteNumbers.
void addCommands(CLI::App& app, CliOptions& options);

// Gives every numeric option of `app` and its subcommands (CLI11 types INT, UINT, FLOAT) a check
// that refuses nan, inf and values beyond float's range such as 1e999: CLI11's Range lets NaN
// through, since every comparison with NaN is false. Run it after the last option is declared.
void requireFiniteNumbers(CLI::App& app);

}  // namespace pathlab::app
