// Technique grid logic: presets, the SPEC field and toggles of the technique set.
#include "ui/estimator/technique_grid.h"

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

// Every connection and equiangular technique up to the maximum: "all", so that it keeps growing
// with the maximum (with the
// set's merges still listed).
TechniqueSet compact(TechniqueSet set, int maxLength) {
  if (set.containsAllUpTo(maxLength, TechniqueFamilies::Connections | TechniqueFamilies::Equiangular))
    set = TechniqueSet::all() | set;
  // Likewise every merge up to the maximum: "m=all".
  if (maxLength >= 2 && covers(set.families(), TechniqueKind::Merge) &&
      set.containsAllUpTo(maxLength, TechniqueFamilies::Merges))
    set |= TechniqueSet::allMerges();
  return set;
}

// All of `group` off when all of it up to maxLength is on, else all of it on.
TechniqueSet toggleGroup(TechniqueSet set, int maxLength, const TechniqueSet& group) {
  const TechniqueRange upTo = techniquesUpTo(maxLength, TechniqueFamilies::All);
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

TechniqueSet toggleMergesOfLength(const TechniqueSet& set, int maxLength, int k) {
  return toggleGroup(set, maxLength, TechniqueSet::mergesOfLength(std::max(k, 2)));
}

TechniqueSet toggleEquiangular(const TechniqueSet& set, int maxLength) {
  TechniqueSet every;
  for (const Technique x : techniquesUpTo(maxLength, TechniqueFamilies::Equiangular)) every.enable(x);
  if (every.empty()) return set;
  return toggleGroup(set, maxLength, every);
}

TechniqueSet toggleAllMerges(const TechniqueSet& set, int maxLength) {
  if (set.containsAllUpTo(maxLength, TechniqueFamilies::Merges)) {
    TechniqueSet off = set;
    off.disable(TechniqueSet::allMerges(), maxLength);
    return off;
  }
  return set | TechniqueSet::allMerges();
}

bool noTechniqueEnabled(const RenderSettings& settings) {
  return settings.integrator != IntegratorKind::Pt && !settings.techniques.anyUpTo(settings.maxLength);
}

bool techniqueShownEnabled(const RenderSettings& settings, Technique x) {
  if (settings.integrator == IntegratorKind::Pt) return !x.isMerge() && x.s <= 1;
  return enabledTechniques(settings).contains(x);
}

}  // namespace pathlab::ui
