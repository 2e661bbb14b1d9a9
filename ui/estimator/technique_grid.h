// The technique grid's edits of the technique set as plain logic (no ImGui): its presets, the
// SPEC field, switching one (s,t), a whole length or a whole s.
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
// Every merge of length k (the grid's merge row label) on or off, as toggleLength.
TechniqueSet toggleMergesOfLength(const TechniqueSet& set, int maxLength, int k);
// Every merge of every length on ("m=all" beside the connections: vertex connection and merging),
// or off when all are on.
TechniqueSet toggleAllMerges(const TechniqueSet& set, int maxLength);
// Every equiangular technique E(1, k), k = 2..maxLength, off when all are on, else all on.
TechniqueSet toggleEquiangular(const TechniqueSet& set, int maxLength);
// True when the settings enable no technique up to their maximum length (Bpt and Lt): the
// renderer cannot run them.
bool noTechniqueEnabled(const RenderSettings& settings);
// Whether the grid ticks technique x: what the integrator really uses. Bpt: the enabled set;
// lt: the enabled set's t = 1 techniques; pt: s <= 1 (its BSDF-sampled hits of emitters and its
// light samples, whatever the set says, which it ignores).
bool techniqueShownEnabled(const RenderSettings& settings, Technique x);

}  // namespace pathlab::ui
