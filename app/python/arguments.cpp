// Keyword arguments to render's options, parsed by CLI11 as the command line is.
#include "app/python/arguments.h"

#include "app/finite_numbers.h"

#include "core/bpt/technique_set.h"

#include <fmt/core.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <span>
#include <vector>

namespace py = pybind11;

namespace pathlab::python {

namespace {

enum class Kind {
  Int,
  Float,
  FloatOrWord,  // a number, or a word the option takes ("auto")
  String,
  Flag,         // True: the option given
  NegatedFlag,  // False: the option given (rr=False is --no-rr)
  Techniques,   // a SPEC string or a TechniqueSet
  Isolation,    // "S,T", "MS,T" or (s, t)
  Colour,       // a file name, "R,G,B" or three numbers
};

struct Argument {
  const char* name;
  const char* option;
  Kind kind;
};

constexpr Argument kSettingsArguments[] = {
    {"width", "--width", Kind::Int},
    {"height", "--height", Kind::Int},
    {"integrator", "--integrator", Kind::String},
    {"max_length", "--max-length", Kind::Int},
    {"mis", "--mis", Kind::String},
    {"beta", "--beta", Kind::Float},
    {"connect", "--connect", Kind::String},
    {"min_connection", "--min-connection", Kind::Float},
    {"light_paths", "--light-paths", Kind::FloatOrWord},
    {"techniques", "--techniques", Kind::Techniques},
    {"isolate", "--isolate", Kind::Isolation},
    {"unweighted", "--unweighted", Kind::Flag},
    {"radius", "--radius", Kind::Float},
    {"radius_alpha", "--radius-alpha", Kind::Float},
    {"noncaustic_photons", "--noncaustic-photons", Kind::Float},
    {"rr", "--no-rr", Kind::NegatedFlag},
    {"medium_sampling", "--medium-sampling", Kind::String},
    {"mlt_variant", "--mlt-variant", Kind::String},
    {"chains", "--chains", Kind::Int},
    {"bootstrap", "--bootstrap", Kind::Int},
    {"large_step", "--large-step", Kind::Float},
    {"sigma", "--sigma", Kind::Float},
    {"mlt_direct", "--mlt-direct", Kind::Int},
    {"seed", "--seed", Kind::Int},
    {"aperture", "--aperture", Kind::Float},
    {"focus_distance", "--focus-distance", Kind::Float},
    {"inject_bias", "--inject-bias", Kind::String},
    {"pyramid", "--pyramid", Kind::Int},
    {"technique_maps", "--technique-maps", Kind::Int},
    {"variance_maps", "--variance-maps", Kind::Int},
    {"check_mis", "--check-mis", Kind::Flag},
    {"threads", "--threads", Kind::Int},
};

constexpr Argument kCheckArguments[] = {
    {"spp", "--spp", Kind::Int},
    {"time", "--time", Kind::Float},
    {"blocks", "--blocks", Kind::Int},
    {"alpha", "--alpha", Kind::Float},
    {"min_hits", "--min-hits", Kind::Int},
    {"radius_levels", "--radius-levels", Kind::Int},
};

constexpr Argument kLoadArguments[] = {
    {"environment", "--environment", Kind::Colour},
    {"environment_strength", "--environment-strength", Kind::Float},
    {"environment_rotation", "--environment-rotation", Kind::Float},
    {"default_light", "--no-default-light", Kind::NegatedFlag},
    {"light_sampler", "--light-sampler", Kind::String},
    {"max_triangles", "--max-triangles", Kind::Int},
};

bool isBool(const py::handle& v) { return py::isinstance<py::bool_>(v); }
bool isInt(const py::handle& v) { return py::isinstance<py::int_>(v) && !isBool(v); }
bool isNumber(const py::handle& v) { return isInt(v) || py::isinstance<py::float_>(v); }

std::string typeName(const py::handle& v) { return py::str(py::type::of(v).attr("__name__")).cast<std::string>(); }

[[noreturn]] void wrongType(const Argument& a, const char* expected, const py::handle& v) {
  throw Error(fmt::format("{}: expected {}, got {}", a.name, expected, typeName(v)));
}

std::string number(const Argument& a, const py::handle& v) {
  if (isInt(v)) return py::str(v).cast<std::string>();
  const double d = v.cast<double>();
  if (!std::isfinite(d)) throw Error(fmt::format("{}: {} is not a finite number", a.name, py::str(v).cast<std::string>()));
  return fmt::format("{}", d);  // the shortest text that reads back as d
}

// The command-line words of one argument (none: a flag left at its default).
std::vector<std::string> words(const Argument& a, const py::handle& v) {
  switch (a.kind) {
    case Kind::Int:
      if (!isInt(v)) wrongType(a, "an int", v);
      return {a.option, py::str(v).cast<std::string>()};
    case Kind::Float:
      if (!isNumber(v)) wrongType(a, "a number", v);
      return {a.option, number(a, v)};
    case Kind::FloatOrWord:
      if (py::isinstance<py::str>(v)) return {a.option, v.cast<std::string>()};
      if (!isNumber(v)) wrongType(a, "a number or a str", v);
      return {a.option, number(a, v)};
    case Kind::String:
      if (!py::isinstance<py::str>(v)) wrongType(a, "a str", v);
      return {a.option, v.cast<std::string>()};
    case Kind::Flag:
    case Kind::NegatedFlag:
      if (!isBool(v)) wrongType(a, "a bool", v);
      if (v.cast<bool>() == (a.kind == Kind::Flag)) return {a.option};
      return {};
    case Kind::Techniques:
      if (py::isinstance<TechniqueSet>(v)) return {a.option, v.cast<const TechniqueSet&>().toString()};
      if (!py::isinstance<py::str>(v)) wrongType(a, "a SPEC str or a TechniqueSet", v);
      return {a.option, v.cast<std::string>()};
    case Kind::Isolation:
      if (py::isinstance<py::str>(v)) return {a.option, v.cast<std::string>()};
      if (py::isinstance<py::tuple>(v) && py::len(v) == 2 && isInt(v[py::int_(0)]) && isInt(v[py::int_(1)]))
        return {a.option, fmt::format("{},{}", py::str(v[py::int_(0)]).cast<std::string>(),
                                      py::str(v[py::int_(1)]).cast<std::string>())};
      wrongType(a, "\"S,T\", \"MS,T\" or a tuple (s, t)", v);
    case Kind::Colour:
      if (py::isinstance<py::str>(v)) return {a.option, v.cast<std::string>()};
      if (py::isinstance<py::sequence>(v) && py::len(v) == 3) {
        const py::sequence rgb = v.cast<py::sequence>();
        std::string text;
        for (size_t i = 0; i < 3; ++i) {
          if (!isNumber(rgb[i])) wrongType(a, "a file name or three numbers", v);
          text += (i ? "," : "") + number(a, rgb[i]);
        }
        return {a.option, text};
      }
      wrongType(a, "a file name or three numbers", v);
  }
  return {};
}

// The command-line words of `kwargs`; refuses an argument not in `table`.
std::vector<std::string> wordsOf(std::span<const Argument> table, const py::kwargs& kwargs, const char* what) {
  std::vector<std::string> args;
  for (const auto& [key, value] : kwargs) {
    const std::string name = py::str(key).cast<std::string>();
    const auto a = std::find_if(table.begin(), table.end(), [&](const Argument& x) { return name == x.name; });
    if (a == table.end()) {
      std::string known;
      for (const Argument& x : table) known += (known.empty() ? "" : ", ") + std::string(x.name);
      throw Error(fmt::format("{}: unknown argument '{}' (it takes {})", what, name, known));
    }
    if (value.is_none()) continue;  // None: the default
    for (std::string& w : words(*a, value)) args.push_back(std::move(w));
  }
  return args;
}

// Parses command-line words with the options `cmd` registers, every number checked finite (and
// an unsigned one not negative) as on the command line.
void parse(CLI::App& cmd, std::vector<std::string> args) {
  app::requireFiniteNumbers(cmd);
  std::reverse(args.begin(), args.end());  // CLI11 takes its arguments from the back
  try {
    cmd.parse(args);
  } catch (const CLI::ParseError& e) {
    throw Error(withArgumentNames(e.what()));
  }
}

}  // namespace

std::string withArgumentNames(const std::string& message) {
  std::vector<Argument> all(std::begin(kSettingsArguments), std::end(kSettingsArguments));
  all.insert(all.end(), std::begin(kLoadArguments), std::end(kLoadArguments));
  all.insert(all.end(), std::begin(kCheckArguments), std::end(kCheckArguments));
  // The longest options first: --radius-alpha before --radius.
  std::sort(all.begin(), all.end(), [](const Argument& a, const Argument& b) {
    return std::string_view(a.option).size() > std::string_view(b.option).size();
  });
  std::string out;
  for (size_t i = 0; i < message.size();) {
    const Argument* hit = nullptr;
    // An option starts the message or follows a space, a quote or a bracket: not inside a path.
    const bool wordStart = i == 0 || std::string_view(" '\"(`").find(message[i - 1]) != std::string_view::npos;
    for (const Argument& a : all) {
      if (!wordStart) break;
      const std::string_view option(a.option);
      const size_t end = i + option.size();
      if (message.compare(i, option.size(), option) == 0 &&
          (end == message.size() || !(std::isalnum(static_cast<unsigned char>(message[end])) || message[end] == '-'))) {
        hit = &a;
        break;
      }
    }
    if (!hit) {
      out += message[i++];
      continue;
    }
    const size_t end = i + std::string_view(hit->option).size();
    // "--no-x" is "x=False".
    out += std::string_view(hit->option).starts_with("--no-") ? fmt::format("{}=False", hit->name) : std::string(hit->name);
    i = end;
  }
  return out;
}

int64_t intArgument(const py::handle& value, const char* name, int64_t lo, int64_t hi) {
  if (!isInt(value)) throw Error(fmt::format("{}: expected an int, got {}", name, typeName(value)));
  int overflow = 0;
  const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
  if (overflow != 0 || v < lo || v > hi)
    throw Error(fmt::format("{}: {} is outside {}..{}", name, py::str(value).cast<std::string>(), lo, hi));
  return v;
}

std::string pathArgument(const py::handle& value, const char* name) {
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__fspath__")) {
    const py::object path = py::module_::import("os").attr("fspath")(value);
    if (py::isinstance<py::str>(path)) return path.cast<std::string>();
  }
  throw Error(fmt::format("{}: expected a path (str or os.PathLike), got {}", name, typeName(value)));
}

std::string settingsArgumentNames() {
  std::string names;
  for (const Argument& a : kSettingsArguments) names += (names.empty() ? "" : ", ") + std::string(a.name);
  return names;
}

app::RenderOptions settingsFromArguments(const py::kwargs& kwargs, std::vector<std::string>& settingsWords) {
  app::RenderOptions o;
  CLI::App cmd("pathlab.Settings");
  app::addRenderEstimateOptions(&cmd, o);
  settingsWords = wordsOf(kSettingsArguments, kwargs, "Settings");
  parse(cmd, settingsWords);
  try {
    app::finishRenderEstimate(o);
    app::checkRequestedPixels(o);
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
  return o;
}

app::SceneOptions loadOptionsFromArguments(const std::string& path, const py::kwargs& kwargs) {
  app::SceneOptions o;
  o.path = path;
  CLI::App cmd("pathlab.load");
  app::addLoadOptions(&cmd, o.load, o.environment);
  parse(cmd, wordsOf(kLoadArguments, kwargs, "load"));
  return o;
}

app::CheckCommandOptions checkFromArguments(const std::vector<std::string>& settingsWords, const py::kwargs& kwargs) {
  app::CheckCommandOptions o;
  CLI::App cmd("pathlab.check");
  app::addCheckOptions(&cmd, o);
  std::vector<std::string> args = settingsWords;
  for (std::string& w : wordsOf(kCheckArguments, kwargs, "check")) args.push_back(std::move(w));
  parse(cmd, args);
  try {
    app::finishCheckOptions(o);
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
  return o;
}

}  // namespace pathlab::python
