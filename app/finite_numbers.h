// The check every numeric option of pathlab's command line gets (and the Python module's
// arguments, parsed by the same registrations).
#pragma once

#include <CLI/CLI.hpp>

namespace pathlab::app {

// Gives every numeric option of `app` and its subcommands (CLI11 types INT, UINT, FLOAT) a check
// that refuses nan, inf and values beyond float's range such as 1e999: CLI11's Range lets NaN
// through, since every comparison with NaN is false. Run it after the last option is declared.
void requireFiniteNumbers(CLI::App& app);

}  // namespace pathlab::app
