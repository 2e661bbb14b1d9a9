// The viewer's edits of the technique choice as plain logic over RenderSettings (no ImGui): the
// presets of the technique grid, toggling one (s,t), the MIS / isolate mode and a change of the
// maximum path length, each producing settings the renderer accepts.
#pragma once

#include "core/bpt/technique_set.h"
#include "core/render/render_settings.h"

#include <string>

namespace pathlab::ui {

// The grid's presets. PathTracing: s <= 1 (camera subpaths, with and without a light sample, the
// path tracer's two techniques). LightTracing: t = 1. OneLength: every technique of one length.
enum class TechniquePreset { All, PathTracing, LightTracing, OneLength, Clear };

const char* presetLabel(TechniquePreset preset);
// The SPEC of a preset; `length` is the length for OneLength. Clear gives "" (no technique).
std::string presetSpec(TechniquePreset preset, int length = 1);

// A SPEC that may be empty (no technique enabled, which TechniqueSet::parse refuses).
TechniqueSet parseOrEmpty(const std::string& spec, int maxLength);
// "all" when every technique up to maxLength is enabled, the explicit "S,T;..." list otherwise.
std::string compactSpec(const TechniqueSet& set);
// The SPEC with (s,t) switched on or off.
std::string toggleTechnique(const std::string& spec, int maxLength, int s, int t);
// True when the settings enable no technique at all (Bpt and Lt): the renderer cannot run them.
bool noTechniqueEnabled(const RenderSettings& settings);

// How the enabled techniques make the image: all combined with MIS, or one technique alone.
enum class EstimatorMode { Combine, IsolateWeighted, IsolateUnweighted };
const char* modeLabel(EstimatorMode mode);
EstimatorMode modeOf(const RenderSettings& settings);
// Isolating uses `target` (s,t); Combine drops the isolation.
void setMode(RenderSettings& settings, EstimatorMode mode, int s, int t);

// A new maximum length: the SPEC is kept when it still parses ("all", "s=0;s=1" grow with it);
// an explicit list loses the techniques that no longer fit; an isolated technique that no longer
// fits is shortened to the longest one with the same s (s = maxLength, t = 1 when s alone
// is too long).
void setMaxLength(RenderSettings& settings, int maxLength);

// True when a weighted isolation shows a technique the set does not enable: its MIS share, and so
// the image, is zero (worth a warning: a black image is otherwise a puzzle).
bool isolatedTechniqueDisabled(const RenderSettings& settings);

// The settings the renderer gets for what the panels show: the path tracer has no isolation and
// no pyramid, so they are dropped (the panels keep them for when bpt comes back).
RenderSettings effectiveSettings(const RenderSettings& edited);

// One line describing the estimator, for the status panel and screenshots.
std::string describe(const RenderSettings& settings);

}  // namespace pathlab::ui
