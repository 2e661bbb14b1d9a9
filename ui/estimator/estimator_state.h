// The estimator the viewer's panels edit, as one value with its edits (no ImGui): the render
// settings, how the enabled techniques make the image (combined, or one technique isolated) and
// which technique the isolate modes show, kept in one place. The renderer gets renderSettings().
#pragma once

#include "core/render/render_settings.h"
#include "ui/presets/presets.h"

#include <string>

namespace pathlab::ui {

// How the enabled techniques make the image: all combined with MIS, or one technique alone.
enum class EstimatorMode { Combine, IsolateWeighted, IsolateUnweighted };
const char* modeLabel(EstimatorMode mode);

struct EstimatorState {
  // Everything but the isolation, which is `mode` and `isolated` (settings.isolate stays empty).
  RenderSettings settings;
  EstimatorMode mode = EstimatorMode::Combine;
  // The technique the isolate modes show; remembered while combining. Always of length
  // 1..settings.maxLength (setMaxLength shortens it).
  Technique isolated{1, 2};
  int oneLength = 2;  // the length of the grid's "one length only" preset, 1..settings.maxLength
  // Metropolis: the chains' time density (MltSummary::density) shown over the image instead of it.
  bool showChainDensity = false;

  // The state of settings (their isolation, if any, becomes mode and isolated).
  static EstimatorState from(const RenderSettings& settings);
};

// The settings the renderer gets: with the isolation of the mode; the path tracer has no
// isolation, no pyramid, no check and no injected bias, so they are dropped (the state keeps them
// for when bpt comes back); the consistency check runs only while combining.
RenderSettings renderSettings(const EstimatorState& state);

// A new maximum length: the technique set is kept ("all", "s=0;s=1" grow with it) less the listed
// techniques that no longer fit (TechniqueSet::fittedTo); an isolated technique that no longer
// fits is shortened to the longest one with the same s (s = maxLength, t = 1 when s alone is too
// long); the one-length preset's length is clamped.
void setMaxLength(EstimatorState& state, int maxLength);
// Picks the technique the isolate modes show; one outside 1..maxLength is ignored (false).
bool setIsolated(EstimatorState& state, Technique x);
// Shows x alone, weighted or unweighted (a click on the pyramid): the path tracer gives way to bpt.
void isolate(EstimatorState& state, Technique x, bool unweighted);
// The next mode (combine, weighted, unweighted); the path tracer gives way to bpt.
void cycleMode(EstimatorState& state);
// Ctrl+digit S: isolate technique (S, k + 1 - S) of the grid's chosen length k (clamped to the
// maximum), the seed's "one path length, every technique" comparison a key per technique. Keeps
// the isolate mode (weighted or unweighted); from combining it isolates the weighted share.
// False (nothing changes) when S > k.
bool isolateOfChosenLength(EstimatorState& state, int chosenLength, int s);
// A preset's estimator (NamedPreset::applyTo); without an isolation of its own the isolated
// technique is kept for the isolate modes.
void applyPreset(EstimatorState& state, const NamedPreset& preset);

// True when a weighted isolation shows a technique the set does not enable: its MIS share, and so
// the image, is zero (worth a warning: a black image is otherwise a puzzle).
bool isolatedTechniqueDisabled(const RenderSettings& settings);

// One line describing the estimator, for the status panel and screenshots.
std::string describe(const RenderSettings& settings);

// The shown image's estimator warning (misOffWarning: which lengths MIS off biases and why), kept
// with the settings and scene it was computed for: recomputed only when either changes.
struct EstimatorWarning {
  RenderSettings settings;
  const Scene* scene = nullptr;
  std::string text;
};
const std::string& estimatorWarning(EstimatorWarning& cache, const Scene* scene, const RenderSettings& settings);

}  // namespace pathlab::ui
