// The viewer's edits of the technique choice as plain logic over RenderSettings (no ImGui): the
// presets of the technique grid, toggling one (s,t), the MIS / isolate mode and a change of the
// maximum path length, each producing settings the renderer accepts.
#pragma once

#include "core/bpt/technique_set.h"
#include "core/render/render_settings.h"

#include <string>

namespace pathlab::ui {

// The grid's presets: TechniqueSet::all, pathTracing (s <= 1), lightTracing (t = 1), ofLength
// (every technique of one length) and the empty set.
enum class TechniquePreset { All, PathTracing, LightTracing, OneLength, Clear };

const char* presetLabel(TechniquePreset preset);
// The set of a preset; `length` is the length for OneLength.
TechniqueSet presetTechniques(TechniquePreset preset, int length = 1);

// What the SPEC field accepts: the SPEC of --techniques, or nothing (the empty set). Throws
// std::invalid_argument on a bad SPEC or one that does not fit maxLength (TechniqueSet::checkFits).
TechniqueSet parseTypedSpec(const std::string& spec, int maxLength);
// The set with the technique switched on or off (a click in the grid), and with a whole length or
// a whole s switched: on when some of it is off, else off. A set that then holds every technique
// up to maxLength becomes TechniqueSet::all, which keeps growing with the maximum.
TechniqueSet toggleTechnique(const TechniqueSet& set, int maxLength, Technique x);
TechniqueSet toggleLength(const TechniqueSet& set, int maxLength, int k);
TechniqueSet toggleLightVertices(const TechniqueSet& set, int maxLength, int s);
// True when the settings enable no technique up to their maximum length (Bpt and Lt): the
// renderer cannot run them.
bool noTechniqueEnabled(const RenderSettings& settings);

// How the enabled techniques make the image: all combined with MIS, or one technique alone.
enum class EstimatorMode { Combine, IsolateWeighted, IsolateUnweighted };
const char* modeLabel(EstimatorMode mode);
EstimatorMode modeOf(const RenderSettings& settings);
// Isolating uses `target` (s,t); Combine drops the isolation.
void setMode(RenderSettings& settings, EstimatorMode mode, int s, int t);

// A new maximum length: the technique set is kept ("all", "s=0;s=1" grow with it) less the listed
// techniques that no longer fit (TechniqueSet::fittedTo); an isolated technique that no longer
// fits is shortened to the longest one with the same s (s = maxLength, t = 1 when s alone is too
// long).
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
