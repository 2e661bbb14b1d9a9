// Technique grid logic: presets, toggles, mode and maximum length over RenderSettings.
#include "ui/technique_grid.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::ui {

const char* presetLabel(TechniquePreset preset) {
  switch (preset) {
    case TechniquePreset::All: return "all";
    case TechniquePreset::PathTracing: return "path tracing (s <= 1)";
    case TechniquePreset::LightTracing: return "light tracing (t = 1)";
    case TechniquePreset::OneLength: return "one length only";
    case TechniquePreset::Clear: return "clear";
  }
  return "?";
}

TechniqueSet presetTechniques(TechniquePreset preset, int length) {
  switch (preset) {
    case TechniquePreset::All: return TechniqueSet::all();
    case TechniquePreset::PathTracing: return TechniqueSet::pathTracing();
    case TechniquePreset::LightTracing: return TechniqueSet::lightTracing();
    case TechniquePreset::OneLength: return TechniqueSet::ofLength(std::max(length, 1));
    case TechniquePreset::Clear: return TechniqueSet();
  }
  return TechniqueSet::all();
}

TechniqueSet parseTypedSpec(const std::string& spec, int maxLength) {
  if (spec.find_first_not_of(" \t;") == std::string::npos) return TechniqueSet();
  const TechniqueSet set = TechniqueSet::parse(spec);
  set.checkFits(maxLength);
  return set;
}

namespace {

// Every technique up to the maximum: "all", so that it keeps growing with the maximum.
TechniqueSet compact(TechniqueSet set, int maxLength) {
  return set.containsAllUpTo(maxLength) ? TechniqueSet::all() : set;
}

// All of `group` off when all of it up to maxLength is on, else all of it on.
TechniqueSet toggleGroup(TechniqueSet set, int maxLength, const TechniqueSet& group) {
  const TechniqueRange upTo = techniquesUpTo(maxLength);
  if (std::all_of(upTo.begin(), upTo.end(), [&](Technique x) { return !group.contains(x) || set.contains(x); })) {
    set.disable(group, maxLength);
    return set;
  }
  return compact(set | group, maxLength);
}

}  // namespace

TechniqueSet toggleTechnique(const TechniqueSet& set, int maxLength, Technique x) {
  TechniqueSet one;
  one.enable(x);
  return toggleGroup(set, maxLength, one);
}

TechniqueSet toggleLength(const TechniqueSet& set, int maxLength, int k) {
  return toggleGroup(set, maxLength, TechniqueSet::ofLength(k));
}

TechniqueSet toggleLightVertices(const TechniqueSet& set, int maxLength, int s) {
  return toggleGroup(set, maxLength, TechniqueSet::withS(s));
}

bool noTechniqueEnabled(const RenderSettings& settings) {
  return settings.integrator != IntegratorKind::Pt && !settings.techniques.anyUpTo(settings.maxLength);
}

const char* modeLabel(EstimatorMode mode) {
  switch (mode) {
    case EstimatorMode::Combine: return "combine with MIS";
    case EstimatorMode::IsolateWeighted: return "isolate, weighted";
    case EstimatorMode::IsolateUnweighted: return "isolate, unweighted";
  }
  return "?";
}

EstimatorMode modeOf(const RenderSettings& settings) {
  if (!settings.isolate) return EstimatorMode::Combine;
  return settings.isolate->unweighted ? EstimatorMode::IsolateUnweighted : EstimatorMode::IsolateWeighted;
}

void setMode(RenderSettings& settings, EstimatorMode mode, int s, int t) {
  if (mode == EstimatorMode::Combine) settings.isolate.reset();
  else settings.isolate = Isolation{s, t, mode == EstimatorMode::IsolateUnweighted};
}

void setMaxLength(RenderSettings& settings, int maxLength) {
  maxLength = std::max(maxLength, 1);
  settings.maxLength = maxLength;
  settings.techniques = settings.techniques.fittedTo(maxLength);
  if (settings.isolate && settings.isolate->s + settings.isolate->t - 1 > maxLength) {
    settings.isolate->s = std::min(settings.isolate->s, maxLength);
    settings.isolate->t = maxLength + 1 - settings.isolate->s;
  }
}

bool isolatedTechniqueDisabled(const RenderSettings& s) {
  if (s.integrator == IntegratorKind::Pt || !s.isolate || s.isolate->unweighted) return false;
  return !s.techniques.contains(s.isolate->s, s.isolate->t);
}

RenderSettings effectiveSettings(const RenderSettings& edited) {
  RenderSettings s = edited;
  if (s.integrator == IntegratorKind::Pt) {
    s.isolate.reset();
    s.pyramidLength = 0;
  }
  return s;
}

std::string describe(const RenderSettings& s) {
  std::string out = fmt::format("{}, max length {}", integratorName(s.integrator), s.maxLength);
  if (s.integrator == IntegratorKind::Pt) return out;
  out += fmt::format(", techniques {}", s.techniques.empty() ? "(none)" : s.techniques.toString());
  if (s.isolate)
    out += fmt::format(", isolate ({},{}) {}", s.isolate->s, s.isolate->t, s.isolate->unweighted ? "unweighted" : "weighted");
  else if (s.mis.heuristic == MisHeuristic::Power)
    out += fmt::format(", MIS power (beta {:g})", s.mis.beta);
  else
    out += fmt::format(", MIS {}", misHeuristicName(s.mis.heuristic));
  if (s.mis.minConnection != kDefaultMinConnection) out += fmt::format(", min connection {:g}", s.mis.minConnection);
  return out;
}

}  // namespace pathlab::ui
