// Presets read at start and applied by key or panel: side A's estimator, the camera, side B.
#include "ui/presets/preset_controller.h"

#include <stdexcept>

namespace pathlab::ui {

std::vector<NamedPreset> loadPresetsOf(ViewerOptions& options) {
  std::vector<NamedPreset> presets;
  if (!options.presetsFile.empty()) presets = loadPresets(options.presetsFile);
  if (!options.preset.empty()) {
    if (options.presetsFile.empty()) throw std::runtime_error("--preset needs --presets FILE");
    const NamedPreset& preset = findPreset(presets, options.preset, options.presetsFile);
    options.settings = preset.applyTo(options.settings);
    // A preset with a side B starts the comparison (an explicit --compare wins).
    if (preset.compare && options.compare.empty()) options.compare = *preset.compare;
  }
  return presets;
}

PresetController::PresetController(std::vector<NamedPreset> presets, const ViewerOptions& options) {
  state_.presets = std::move(presets);
  state_.path = options.presetsFile;
  if (!options.preset.empty())
    for (size_t i = 0; i < state_.presets.size(); ++i)
      if (state_.presets[i].name == options.preset) state_.current = static_cast<int>(i);
}

void PresetController::apply(int index, const PresetTarget& target) {
  const int n = static_cast<int>(state_.presets.size());
  if (n == 0) return;
  state_.current = (index % n + n) % n;
  const NamedPreset& p = state_.presets[static_cast<size_t>(state_.current)];
  applyPreset(target.estimator, p);
  if (p.camera) target.orbit = OrbitCamera(*p.camera, target.scene.boundsMin(), target.scene.boundsMax());
  // A preset with a side B sets both sides (checked when the presets were loaded); one without
  // leaves the comparison as it is.
  if (p.compare && !applyCompareConfig(target.compare, *p.compare, renderSettings(target.estimator))) {
    target.message.show("preset " + p.name + ": " + target.compare.error, true);
    return;
  }
  target.message.show("preset: " + p.name);
}

}  // namespace pathlab::ui
