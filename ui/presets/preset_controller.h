// The lecture's presets in the viewer: reading them (and --preset) before the window opens, the
// one applied last, and applying one to side A, the camera and, when it has one, side B.
#pragma once

#include "core/scene/scene.h"
#include "ui/estimator/estimator_state.h"
#include "ui/lane/compare.h"
#include "ui/message_line.h"
#include "ui/presets/presets.h"
#include "ui/scene/orbit_camera.h"
#include "ui/viewer_options.h"
#include "ui/viewer_state.h"

#include <vector>

namespace pathlab::ui {

// The presets of --presets FILE; --preset NAME applied to `options` (its estimator, and its side B
// unless --compare gives one). Throws PresetError (or std::runtime_error for --preset alone).
std::vector<NamedPreset> loadPresetsOf(ViewerOptions& options);

// What applying a preset changes.
struct PresetTarget {
  EstimatorState& estimator;
  OrbitCamera& orbit;
  CompareState& compare;
  const Scene& scene;  // bounds the orbit of a preset's camera
  MessageLine& message;
};

class PresetController {
 public:
  // `options.preset`, when given, is the current one (already applied to the starting estimator).
  PresetController(std::vector<NamedPreset> presets, const ViewerOptions& options);
  // What the Presets section shows and chooses from.
  const PresetState& state() const { return state_; }
  // Applies preset `index`, counted round (the next after the last is the first).
  void apply(int index, const PresetTarget& target);
  void next(const PresetTarget& target) { apply(state_.current + 1, target); }
  void previous(const PresetTarget& target) { apply(state_.current < 0 ? -1 : state_.current - 1, target); }

 private:
  PresetState state_;
};

}  // namespace pathlab::ui
