// Side B's estimator from a CONFIG, its settings in side A's view, swapping, and the split of the room.
#include "ui/lane/compare.h"

#include "core/converge/convergence_config.h"

#include <fmt/core.h>

#include <algorithm>
#include <thread>
#include <tuple>
#include <vector>

namespace pathlab::ui {

namespace {

// The view both sides share; everything else is the estimator.
void copyView(RenderSettings& to, const RenderSettings& from) {
  const auto view = [](auto& s) { return std::tie(s.width, s.height, s.camera, s.lens, s.seed, s.russianRoulette, s.checkMis); };
  view(to) = view(from);
}

}  // namespace

EstimatorState compareEstimator(const std::string& config, const RenderSettings& a, const std::string& option) {
  RenderSettings base;
  copyView(base, a);
  base.maxLength = a.maxLength;
  base.integrator = IntegratorKind::Bpt;
  std::vector<ConvergenceConfig> parsed;
  try {
    parsed = parseConvergenceConfigs(config, base);
  } catch (const std::invalid_argument& e) {
    // The parser speaks of converge's --configs; here the text came from `option` (issue 37).
    std::string what = e.what();
    if (const std::string converge = "--configs: "; what.rfind(converge, 0) == 0) what.erase(0, converge.size());
    throw std::invalid_argument(option + ": " + what);
  }
  if (parsed.size() != 1)
    throw std::invalid_argument(fmt::format("{} {}: one configuration, not {}", option, config, parsed.size()));
  return EstimatorState::from(parsed.front().settings);
}

RenderSettings compareRenderSettings(const EstimatorState& b, const RenderSettings& a) {
  RenderSettings s = renderSettings(b);
  copyView(s, a);
  s.pyramidLength = 0;
  s.techniqueMaps = false;
  s.varianceMaps = false;
  s.checkTechniques = false;
  return s;
}

std::string configText(const RenderSettings& s) {
  std::string out = integratorName(s.integrator);
  std::vector<std::string> keys;
  const RenderSettings defaults;
  if (s.integrator != IntegratorKind::Pt) {
    if (s.mis.heuristic != defaults.mis.heuristic) keys.push_back(fmt::format("mis={}", misHeuristicName(s.mis.heuristic)));
    if (s.mis.heuristic == MisHeuristic::Power && s.mis.beta != defaults.mis.beta)
      keys.push_back(fmt::format("beta={}", s.mis.beta));
    if (s.mis.minConnection != defaults.mis.minConnection)
      keys.push_back(fmt::format("min-connection={}", s.mis.minConnection));
    if (!(s.techniques == TechniqueSet::all())) keys.push_back("techniques=" + s.techniques.toString());
    if (s.connect != defaults.connect) keys.push_back(fmt::format("connect={}", connectStrategyName(s.connect)));
  }
  keys.push_back(fmt::format("max-length={}", s.maxLength));
  for (size_t i = 0; i < keys.size(); ++i) out += (i == 0 ? ":" : ",") + keys[i];
  return out;
}

bool applyCompareConfig(CompareState& compare, const std::string& config, const RenderSettings& a) {
  try {
    compare.b = compareEstimator(config, a);
  } catch (const std::exception& e) {
    compare.error = e.what();
    return false;
  }
  compare.error.clear();
  compare.typed = configText(compare.b.settings);
  compare.on = true;
  return true;
}

void swapSides(CompareState& compare, EstimatorState& a) {
  std::swap(compare.b, a);
  compare.typed = configText(compare.b.settings);
  compare.error.clear();
}

std::pair<PixelRect, PixelRect> splitRoom(const PixelRect& room, std::optional<float> aspect, int gap) {
  auto halves = [&](bool sideBySide) {
    PixelRect first = room, second = room;
    if (sideBySide) {
      first.size.x = std::max((room.size.x - gap) / 2, 0);
      second.size.x = first.size.x;
      second.origin.x = room.origin.x + room.size.x - second.size.x;
    } else {
      first.size.y = std::max((room.size.y - gap) / 2, 0);
      second.size.y = first.size.y;
      second.origin.y = room.origin.y + room.size.y - second.size.y;
    }
    return std::pair{fitAspect(first, aspect), fitAspect(second, aspect)};
  };
  const auto wide = halves(true), tall = halves(false);
  const auto area = [](const PixelRect& r) { return static_cast<long>(r.size.x) * r.size.y; };
  return area(tall.first) > area(wide.first) ? tall : wide;
}

int threadsPerSide(int threads) {
  const int all = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, all / 2);
}

}  // namespace pathlab::ui
