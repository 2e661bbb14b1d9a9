// The A/B comparison (issue 14): a second estimator of the same scene and view, rendered beside the
// main one by a renderer of its own with an equal share of the threads — the lecture's "path
// tracing on the left, BPT on the right, same time". Side A is the viewer's estimator, edited by
// every panel and shortcut; side B is entered as a CONFIG of `pathlab converge` (or swapped in
// from A). The view (scene, camera, lens, size, seed, Russian roulette) is shared: moving the
// camera restarts both. No ImGui, no OpenGL here: state, settings and layout.
#pragma once

#include "core/render/render_settings.h"
#include "ui/display/image_rect.h"
#include "ui/estimator/estimator_state.h"

#include <optional>
#include <string>
#include <utility>

namespace pathlab::ui {

struct CompareState {
  bool on = false;
  EstimatorState b;    // side B's estimator
  std::string typed;   // the CONFIG field (side B's configuration as last applied or swapped in)
  std::string error;   // why the CONFIG typed last was refused ("" when it was not)
};

// Side B's estimator from a CONFIG as `pathlab converge --configs` takes one (INTEGRATOR[:key=value,
// ...], core/converge/convergence_config.h): the default estimator (all techniques, balance
// heuristic, path reuse, no isolation) changed by the CONFIG's keys, at side A's maximum length
// unless the CONFIG sets one. Throws std::invalid_argument with the parser's one line, starting
// with `option` (where the CONFIG came from: the command line's --compare, a preset's "compare").
EstimatorState compareEstimator(const std::string& config, const RenderSettings& a,
                                const std::string& option = "--compare");

// The settings side B's renderer gets: B's estimator (renderSettings) in A's view — A's size,
// camera, lens, seed and Russian roulette. The pyramid, the technique maps and the consistency check
// follow side A only (B renders none of them).
RenderSettings compareRenderSettings(const EstimatorState& b, const RenderSettings& a);

// The CONFIG text of an estimator, canonical (it parses back to the same estimator, keys left at
// their defaults omitted): "pt", "bpt:mis=power,techniques=t=1". An isolation has no CONFIG key and
// is left out (describe() names it).
std::string configText(const RenderSettings& settings);

// Sets side B from `config` (compare.error says why not, and B is kept); turns the comparison on.
bool applyCompareConfig(CompareState& compare, const std::string& config, const RenderSettings& a);
// Exchanges the sides' estimators; the CONFIG field shows B's new configuration.
void swapSides(CompareState& compare, EstimatorState& a);

// The two images' rectangles in the room the panels leave: side by side, or one above the other
// when that shows them larger (a tall room), each the largest of `aspect` in its half, `gap`
// pixels apart. No aspect: each half whole.
std::pair<PixelRect, PixelRect> splitRoom(const PixelRect& room, std::optional<float> aspect, int gap);

// Render threads of each side: half of `threads` (0: all hardware threads), at least one.
int threadsPerSide(int threads);

}  // namespace pathlab::ui
