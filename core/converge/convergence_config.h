// The configurations `pathlab converge` compares: a `;`-separated list of
// INTEGRATOR[:key=value[,key=value...]] (bpt, pt, lt, vcm or bpm) with keys mis, beta, min-connection,
// techniques, max-length, connect (all or endpoints), radius and radius-alpha (of the merges).
#pragma once

#include "core/render/render_settings.h"

#include <string>
#include <vector>

namespace pathlab {

struct ConvergenceConfig {
  std::string label;  // the configuration's text, trimmed (names its line in the CSV and the plot)
  RenderSettings settings;
};

// Each configuration starts from `base` (size, seed, maximum length, Russian roulette, lens).
// A technique SPEC contains ';' and ',' itself ("bpt:techniques=1,2;k=3,mis=power"), so a ';'
// separates configurations only when an integrator name follows it (bpt, pt, lt, then ':' ';' or
// the end) and a ',' separates keys only when a known key and '=' follow it: no SPEC item starts
// that way. Throws std::invalid_argument with one line naming the bad configuration; every
// configuration passes validateSettings.
std::vector<ConvergenceConfig> parseConvergenceConfigs(const std::string& text, const RenderSettings& base);

}  // namespace pathlab
