// Keyword arguments as the command line's options: pathlab.Settings(...) and pathlab.load(...)
// turn each argument into the option `render` takes (max_length=5 -> --max-length 5) and parse
// them with render's own registrations (app/render_command.h, app/shared_options.h), so every
// option means, checks and refuses exactly what it does on the command line. The messages then
// name the Python argument instead of the option.
#pragma once

#include "app/check_command.h"
#include "app/render_command.h"

#include <pybind11/pybind11.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab::python {

// pathlab.Error: a refused argument or a failed call, with the one line the CLI prints.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Settings(**kwargs): render's estimate options (addRenderEstimateOptions), checked as render
// checks them before loading the scene (finishRenderEstimate).
// `words`: the command-line words they became, for commands that take the same options
// (checkFromArguments).
app::RenderOptions settingsFromArguments(const pybind11::kwargs& kwargs, std::vector<std::string>& words);
// The keyword arguments Settings accepts, in the stub's order.
std::string settingsArgumentNames();

// pathlab.check's options: the Settings' words (an option of render that check does not take is
// refused, named) and check's own keyword arguments (spp, time, blocks, alpha, min_hits,
// radius_levels), parsed by check's registrations and checked as `pathlab check` does.
app::CheckCommandOptions checkFromArguments(const std::vector<std::string>& settingsWords, const pybind11::kwargs& kwargs);

// load(path, **kwargs): how the scene loads (--environment ..., --light-sampler, --max-triangles).
app::SceneOptions loadOptionsFromArguments(const std::string& path, const pybind11::kwargs& kwargs);

// An int argument within [lo, hi] (not a bool), else a one-line Error naming it.
int64_t intArgument(const pybind11::handle& value, const char* name, int64_t lo, int64_t hi);
// A path: a str or an os.PathLike.
std::string pathArgument(const pybind11::handle& value, const char* name);

// A message of the command line's with its options named as the Python arguments:
// "--radius-alpha 1.5 is outside" -> "radius_alpha 1.5 is outside", "--no-rr" -> "rr=False".
std::string withArgumentNames(const std::string& message);

}  // namespace pathlab::python
