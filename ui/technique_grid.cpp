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

std::string presetSpec(TechniquePreset preset, int length) {
  switch (preset) {
    case TechniquePreset::All: return "all";
    case TechniquePreset::PathTracing: return "s=0;s=1";
    case TechniquePreset::LightTracing: return "t=1";
    case TechniquePreset::OneLength: return "k=" + std::to_string(length);
    case TechniquePreset::Clear: return "";
  }
  return "all";
}

TechniqueSet parseOrEmpty(const std::string& spec, int maxLength) {
  if (spec.find_first_not_of(" \t;") == std::string::npos) return TechniqueSet(maxLength);
  return TechniqueSet::parse(spec, maxLength);
}

std::string compactSpec(const TechniqueSet& set) {
  return set == TechniqueSet::all(set.maxLength()) ? "all" : set.toString();
}

std::string toggleTechnique(const std::string& spec, int maxLength, int s, int t) {
  TechniqueSet set = parseOrEmpty(spec, maxLength);  // throws on a bad SPEC
  if (set.contains(s, t)) set.disable(s, t);
  else set.enable(s, t);
  return compactSpec(set);
}

bool noTechniqueEnabled(const RenderSettings& settings) {
  if (settings.integrator == IntegratorKind::Pt) return false;
  try {
    return parseOrEmpty(settings.techniques, settings.maxLength).size() == 0;
  } catch (const std::invalid_argument&) {
    return false;  // a bad SPEC is the renderer's to refuse, with its message
  }
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
  const int oldMax = settings.maxLength;
  settings.maxLength = maxLength;
  try {
    parseOrEmpty(settings.techniques, maxLength);
  } catch (const std::invalid_argument&) {
    // An explicit list with techniques longer than the new maximum: keep the ones that fit.
    try {
      const TechniqueSet old = parseOrEmpty(settings.techniques, oldMax);
      TechniqueSet fitted(maxLength);
      for (int k = 1; k <= std::min(oldMax, maxLength); ++k)
        for (int s = 0; s <= k; ++s)
          if (old.contains(s, k + 1 - s)) fitted.enable(s, k + 1 - s);
      settings.techniques = compactSpec(fitted);
    } catch (const std::invalid_argument&) {
      // Not valid before either: left for the renderer to refuse.
    }
  }
  if (settings.isolate && settings.isolate->s + settings.isolate->t - 1 > maxLength) {
    settings.isolate->s = std::min(settings.isolate->s, maxLength);
    settings.isolate->t = maxLength + 1 - settings.isolate->s;
  }
}

bool isolatedTechniqueDisabled(const RenderSettings& s) {
  if (s.integrator == IntegratorKind::Pt || !s.isolate || s.isolate->unweighted) return false;
  try {
    return !parseOrEmpty(s.techniques, s.maxLength).contains(s.isolate->s, s.isolate->t);
  } catch (const std::invalid_argument&) {
    return false;
  }
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
  out += fmt::format(", techniques {}", s.techniques.empty() ? "(none)" : s.techniques);
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
