// The viewer's estimator state and its edits (see the header).
#include "ui/estimator/estimator_state.h"

#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

// Moves an isolation out of the settings into the mode and the isolated technique.
void takeIsolation(EstimatorState& state, RenderSettings settings) {
  if (settings.isolate) {
    state.mode = settings.isolate->unweighted ? EstimatorMode::IsolateUnweighted : EstimatorMode::IsolateWeighted;
    state.isolated = settings.isolate->technique();
  } else {
    state.mode = EstimatorMode::Combine;
  }
  settings.isolate.reset();
  state.settings = std::move(settings);
  setMaxLength(state, state.settings.maxLength);  // the isolated technique and oneLength fit
}

void preferBidirectional(EstimatorState& state) {
  if (state.settings.integrator == IntegratorKind::Pt) state.settings.integrator = IntegratorKind::Bpt;
}

}  // namespace

const char* modeLabel(EstimatorMode mode) {
  switch (mode) {
    case EstimatorMode::Combine: return "combine with MIS";
    case EstimatorMode::IsolateWeighted: return "isolate, weighted";
    case EstimatorMode::IsolateUnweighted: return "isolate, unweighted";
  }
  return "?";
}

EstimatorState EstimatorState::from(const RenderSettings& settings) {
  EstimatorState state;
  takeIsolation(state, settings);
  return state;
}

RenderSettings renderSettings(const EstimatorState& state) {
  RenderSettings s = state.settings;
  if (s.integrator == IntegratorKind::Pt) {
    s.isolate.reset();
    s.pyramidLength = 0;
    s.checkTechniques = false;
    s.injectBias.reset();
  } else if (s.integrator == IntegratorKind::Mlt) {
    // Metropolis runs over the connections the set keeps (not its merges), every sample of a chain
    // through the same weights: no isolation, pyramid, maps, check or injected bias.
    s.techniques = s.techniques & TechniqueSet::all();
    s.isolate.reset();
    s.pyramidLength = 0;
    s.techniqueMaps = false;
    s.varianceMaps = false;
    s.checkTechniques = false;
    s.injectBias.reset();
  } else if (state.mode != EstimatorMode::Combine) {
    s.isolate = Isolation{state.isolated.s, state.isolated.t, state.mode == EstimatorMode::IsolateUnweighted,
                          state.isolated.kind};
    s.checkTechniques = false;  // it compares the enabled techniques, which isolation does not run
  }
  return s;
}

void setMaxLength(EstimatorState& state, int maxLength) {
  maxLength = std::max(maxLength, 1);
  state.settings.maxLength = maxLength;
  state.settings.techniques = state.settings.techniques.fittedTo(maxLength);
  if (state.isolated.length() > maxLength && state.isolated.isMerge() && maxLength >= 2) {
    // A merge of the longest length left: M(s, k + 2 - s), s >= 2.
    state.isolated.s = std::clamp(state.isolated.s, 2, maxLength);
    state.isolated.t = maxLength + 2 - state.isolated.s;
  } else if (state.isolated.length() > maxLength && state.isolated.isEquiangular() && maxLength >= 2) {
    state.isolated = Technique::equiangular(maxLength);  // the longest E(1, k) left
  } else if (state.isolated.length() > maxLength) {
    state.isolated = Technique{std::min(state.isolated.s, maxLength), maxLength + 1 - std::min(state.isolated.s, maxLength)};
  }
  state.oneLength = std::min(state.oneLength, maxLength);
  state.settings.mlt.directLength = std::min(state.settings.mlt.directLength, maxLength);
}

bool setIsolated(EstimatorState& state, Technique x) {
  if (!x.valid() || x.length() > state.settings.maxLength) return false;
  state.isolated = x;
  return true;
}

void isolate(EstimatorState& state, Technique x, bool unweighted) {
  preferBidirectional(state);
  if (!setIsolated(state, x)) return;
  state.mode = unweighted ? EstimatorMode::IsolateUnweighted : EstimatorMode::IsolateWeighted;
}

bool isolateOfChosenLength(EstimatorState& state, int chosenLength, int s) {
  const int k = std::clamp(chosenLength, 1, state.settings.maxLength);
  if (s < 0 || s > k) return false;
  const bool unweighted = state.mode == EstimatorMode::IsolateUnweighted;
  isolate(state, Technique{s, k + 1 - s}, unweighted);
  return true;
}

void cycleMode(EstimatorState& state) {
  preferBidirectional(state);
  state.mode = static_cast<EstimatorMode>((static_cast<int>(state.mode) + 1) % 3);
}

void applyPreset(EstimatorState& state, const NamedPreset& preset) {
  takeIsolation(state, preset.applyTo(state.settings));
}

bool isolatedTechniqueDisabled(const RenderSettings& s) {
  if (s.integrator == IntegratorKind::Pt || !s.isolate || s.isolate->unweighted) return false;
  return !s.techniques.contains(s.isolate->technique());
}

std::string describe(const RenderSettings& s) {
  std::string out = fmt::format("{}, max length {}", integratorName(s.integrator), s.maxLength);
  // What each integrator really does: the path tracer weighs its light sample against BSDF
  // sampling with the power heuristic; light tracing has one technique per length, t = 1.
  if (s.integrator == IntegratorKind::Pt)
    return out + ", light sample + BSDF sampling, MIS power (beta 2)" +
           (s.mediumSampling ? fmt::format(", medium sampling {}", mediumSamplingName(*s.mediumSampling)) : "");
  const TechniqueSet enabled = enabledTechniques(s);
  out += fmt::format(", techniques {}", enabled.empty() ? "(none)" : enabled.toString());
  if (s.integrator == IntegratorKind::Lt && !s.isolate) {
    out += ", one technique a length (weight 1)";
  } else if (s.isolate)
    out += fmt::format(", isolate {} {}", techniqueLabel(s.isolate->technique()), s.isolate->unweighted ? "unweighted" : "weighted");
  else if (s.mis.heuristic == MisHeuristic::Power)
    out += fmt::format(", MIS power (beta {:g})", s.mis.beta);
  else
    out += fmt::format(", MIS {}", misHeuristicName(s.mis.heuristic));
  if (s.mis.minConnection != kDefaultMinConnection) out += fmt::format(", min connection {:g}", s.mis.minConnection);
  if (covers(enabled.families(), TechniqueKind::Merge))
    out += fmt::format(", merging radius {:g} alpha {:g}{}{}", firstMergeRadius(s), s.mergeRadiusAlpha,
                       s.mergeSite == MergeSite::FirstNonSpecular ? " at the first non-specular camera vertex (ppm)" : "",
                       s.mergeNonCaustic ? fmt::format(", non-caustic photons {:g}", *s.mergeNonCaustic) : "");
  if (s.connect != ConnectStrategy::All) out += fmt::format(", connect {}", connectStrategyName(s.connect));
  // bpt's equiangular techniques E(1, k) (issue 35): the A | B lanes of the fog preset differ in
  // this. Said when chosen (the default, E beside C where a fog allows, goes without saying).
  if (s.mediumSampling && s.integrator == IntegratorKind::Bpt)
    out += *s.mediumSampling == MediumSampling::Distance ? std::string(", distance sampling alone in media (no E(1,k))")
                                                         : fmt::format(", equiangular E(1,k) {}",
                                                                       *s.mediumSampling == MediumSampling::Mis
                                                                           ? "beside C(1,k)"
                                                                           : "in place of C(1,k)");
  if (s.lightPathsAuto) out += ", light paths auto";
  else if (s.lightPaths != 1.f) out += fmt::format(", light paths {:g}", s.lightPaths);
  if (s.integrator == IntegratorKind::Mlt) {
    // What decides the chains (the A | B lanes of two Metropolis settings differ in these).
    const MltOptions& m = s.mlt;
    out += fmt::format(", {} chains {}, large step {:g}, sigma {:g}, bootstrap {}", mltVariantName(m.variant), m.chains,
                       m.largeStep, m.sigma, m.bootstrap);
    if (m.directLength > 0) out += fmt::format(", up to {} edges by BPT", m.directLength);
  }
  if (s.injectBias)
    out += fmt::format(", BIAS INJECTED: {} x {:g}", techniqueLabel(s.injectBias->technique()), s.injectBias->factor);
  return out;
}

const std::string& estimatorWarning(EstimatorWarning& cache, const Scene* scene, const RenderSettings& settings) {
  if (cache.scene != scene || !(cache.settings == settings)) {
    cache.scene = scene;
    cache.settings = settings;
    cache.text = scene ? misOffWarning(*scene, settings) : std::string();
    if (const std::string w = scene ? optimalMisWarning(*scene, settings) : std::string(); !w.empty())
      cache.text += (cache.text.empty() ? "" : "\n") + w;
    if (settings.injectBias && settings.integrator != IntegratorKind::Pt) {
      if (!cache.text.empty()) cache.text += "\n";
      cache.text += fmt::format("technique {} is multiplied by {:g} (inject bias): this image is deliberately wrong",
                                techniqueLabel(settings.injectBias->technique()), settings.injectBias->factor);
    }
  }
  return cache.text;
}

}  // namespace pathlab::ui
