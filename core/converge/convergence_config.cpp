// Parsing of `pathlab converge --configs` (grammar in the header).
#include "core/converge/convergence_config.h"

#include <fmt/core.h>

#include <array>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <string_view>

namespace pathlab {

namespace {

// vcm and bpm are bpt with a technique set of their own, as on the command line.
constexpr std::array<std::string_view, 6> kIntegrators = {"bpt", "pt", "lt", "vcm", "bpm", "mlt"};
constexpr std::array<std::string_view, 17> kKeys = {
    "mis",        "beta",         "min-connection",     "techniques",      "max-length",
    "connect",    "radius",       "radius-alpha",       "noncaustic-photons", "medium-sampling",
    "mlt-variant", "chains",      "bootstrap",          "large-step",      "sigma",
    "mlt-direct", "light-paths"};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// True when `rest` (what follows a ';') starts a new configuration.
bool startsConfig(std::string_view rest) {
  rest = trim(rest);
  if (rest.empty() || rest.front() == ';') return true;  // an empty configuration, skipped
  for (std::string_view name : kIntegrators)
    if (rest.substr(0, name.size()) == name &&
        (rest.size() == name.size() || rest[name.size()] == ':' || rest[name.size()] == ';'))
      return true;
  return false;
}

// True when `rest` (what follows a ',') starts a new key=value pair.
bool startsKey(std::string_view rest) {
  rest = trim(rest);
  for (std::string_view key : kKeys)
    if (rest.substr(0, key.size()) == key && rest.size() > key.size() && rest[key.size()] == '=') return true;
  return false;
}

std::vector<std::string_view> splitWhere(std::string_view text, char sep, bool (*startsNext)(std::string_view)) {
  std::vector<std::string_view> parts;
  size_t begin = 0;
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == sep && startsNext(text.substr(i + 1))) {
      parts.push_back(text.substr(begin, i - begin));
      begin = i + 1;
    }
  parts.push_back(text.substr(begin));
  return parts;
}

[[noreturn]] void fail(std::string_view config, const std::string& problem) {
  throw std::invalid_argument(fmt::format("--configs: '{}': {}", config, problem));
}

template <typename T>
T parseNumber(std::string_view config, std::string_view key, std::string_view text) {
  T v{};
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec == std::errc::result_out_of_range && ptr == text.data() + text.size())
    fail(config, fmt::format("{}={} is out of range (overflows)", key, text));
  if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
    fail(config, fmt::format("{}={} is not a number", key, text));
  return v;
}

ConvergenceConfig parseOne(std::string_view config, const RenderSettings& base) {
  ConvergenceConfig c{std::string(config), base};
  RenderSettings& s = c.settings;
  const size_t colon = config.find(':');
  const std::string_view name = trim(config.substr(0, colon));
  if (name == "bpt") s.integrator = IntegratorKind::Bpt;
  else if (name == "pt") s.integrator = IntegratorKind::Pt;
  else if (name == "lt") s.integrator = IntegratorKind::Lt;
  else if (name == "vcm") s.integrator = IntegratorKind::Bpt, s.techniques = TechniqueSet::parse("all;m=all");
  else if (name == "bpm") s.integrator = IntegratorKind::Bpt, s.techniques = TechniqueSet::parse("m=all");
  else if (name == "mlt") s.integrator = IntegratorKind::Mlt;
  else fail(config, fmt::format("unknown integrator '{}' (bpt, pt, lt, vcm, bpm or mlt)", name));
  if (colon != std::string_view::npos) {
    const std::string_view keys = config.substr(colon + 1);
    for (std::string_view pair : splitWhere(keys, ',', startsKey)) {
      pair = trim(pair);
      const size_t eq = pair.find('=');
      if (eq == std::string_view::npos) fail(config, fmt::format("'{}' is not key=value", pair));
      const std::string_view key = trim(pair.substr(0, eq)), value = trim(pair.substr(eq + 1));
      const bool estimatorKey = key == "mis" || key == "beta" || key == "min-connection" || key == "techniques" ||
                                key == "connect" || key == "radius" || key == "radius-alpha";
      if (key == "techniques" && (name == "vcm" || name == "bpm"))
        fail(config, fmt::format("{} sets the techniques: for another set use bpt:techniques=...", name));
      if (estimatorKey && s.integrator == IntegratorKind::Pt)
        fail(config, fmt::format("{} applies to bpt and lt, not pt", key));
      const bool mltKey = key == "mlt-variant" || key == "chains" || key == "bootstrap" || key == "large-step" ||
                          key == "sigma" || key == "mlt-direct";
      if (mltKey && s.integrator != IntegratorKind::Mlt)
        fail(config, fmt::format("{} applies to mlt, not {}", key, name));
      if (key == "mis") {
        if (const std::optional<MisHeuristic> h = misHeuristicFromName(value)) s.mis.heuristic = *h;
        else fail(config, fmt::format("unknown MIS heuristic '{}' ({})", value, kMisHeuristicNames));
      } else if (key == "connect") {
        if (value == "all") s.connect = ConnectStrategy::All;
        else if (value == "endpoints") s.connect = ConnectStrategy::Endpoints;
        else fail(config, fmt::format("unknown connect strategy '{}' (all or endpoints)", value));
      } else if (key == "beta") {
        s.mis.beta = parseNumber<float>(config, key, value);
        if (!(s.mis.beta >= 0.01f && s.mis.beta <= 100.f)) fail(config, "beta is outside 0.01..100");
      } else if (key == "min-connection") {
        s.mis.minConnection = parseNumber<float>(config, key, value);
        if (!(s.mis.minConnection >= 0.f && s.mis.minConnection <= 1.f)) fail(config, "min-connection is outside 0..1");
      } else if (key == "techniques") {
        try {
          s.techniques = TechniqueSet::parse(std::string(value));
        } catch (const std::invalid_argument& e) {
          fail(config, e.what());
        }
      } else if (key == "radius") {
        s.mergeRadius = parseNumber<float>(config, key, value);  // validateSettings checks the range
      } else if (key == "radius-alpha") {
        s.mergeRadiusAlpha = parseNumber<float>(config, key, value);
      } else if (key == "noncaustic-photons") {
        s.mergeNonCaustic = parseNumber<float>(config, key, value);
      } else if (key == "medium-sampling") {
        s.mediumSampling = parseMediumSampling(value);
        if (!s.mediumSampling) fail(config, fmt::format("unknown medium sampling '{}' (distance, equiangular or mis)", value));
      } else if (key == "mlt-variant") {
        const std::optional<MltVariant> v = parseMltVariant(value);
        if (!v) fail(config, fmt::format("unknown MLT variant '{}' (mmlt or pss)", value));
        s.mlt.variant = *v;
      } else if (key == "chains") {
        s.mlt.chains = parseNumber<int>(config, key, value);  // validateSettings checks the ranges
      } else if (key == "bootstrap") {
        s.mlt.bootstrap = parseNumber<uint64_t>(config, key, value);
      } else if (key == "large-step") {
        s.mlt.largeStep = parseNumber<float>(config, key, value);
      } else if (key == "sigma") {
        s.mlt.sigma = parseNumber<float>(config, key, value);
      } else if (key == "mlt-direct") {
        s.mlt.directLength = parseNumber<int>(config, key, value);
      } else if (key == "light-paths") {
        // validateSettings checks the range and integrator
        if (value == "auto") s.lightPathsAuto = true, s.lightPaths = 1.f;
        else s.lightPathsAuto = false, s.lightPaths = parseNumber<float>(config, key, value);
      } else if (key == "max-length") {
        s.maxLength = parseNumber<int>(config, key, value);
        if (s.maxLength < 1 || s.maxLength > 100000) fail(config, "max-length is outside 1..100000");
      } else {
        fail(config, fmt::format("unknown key '{}' (mis, beta, min-connection, techniques, max-length, connect, radius, "
                                  "radius-alpha, noncaustic-photons, medium-sampling, mlt-variant, chains, bootstrap, "
                                  "large-step, sigma, mlt-direct, light-paths)",
                                  key));
      }
    }
  }
  try {
    validateSettings(s);
  } catch (const std::exception& e) {
    fail(config, e.what());
  }
  return c;
}

}  // namespace

std::vector<ConvergenceConfig> parseConvergenceConfigs(const std::string& text, const RenderSettings& base) {
  std::vector<ConvergenceConfig> configs;
  for (std::string_view config : splitWhere(text, ';', startsConfig)) {
    config = trim(config);
    if (config.empty()) continue;  // a trailing or doubled ';'
    configs.push_back(parseOne(config, base));
  }
  if (configs.empty()) throw std::invalid_argument("--configs: no configuration given");
  for (size_t i = 0; i < configs.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (configs[i].label == configs[j].label)
        throw std::invalid_argument(fmt::format("--configs: '{}' is given twice", configs[i].label));
  return configs;
}

}  // namespace pathlab
