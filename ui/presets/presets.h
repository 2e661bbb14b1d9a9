// Named presets of the lecture mode: a saved estimator state (integrator, technique set, MIS
// heuristic, maximum length, isolation) and optionally a camera, read from a JSON file:
//
//   {"presets": [{"name": "path tracing", "integrator": "bpt", "techniques": "s=0;s=1",
//                 "mis": "power", "beta": 2, "minConnection": 0.001, "maxLength": 8, "isolate": [1, 2],
//                 "unweighted": true,
//                 "camera": {"eye": [0, 1, 3.9], "target": [0, 1, 0], "yfovDegrees": 39.6},
//                 "compare": "bpt:mis=power"}]}
//
// "integrator" is also "vcm", "bpm" or "ppm" (bpt with their own technique set, as on the command
// line); "isolate" is also a string "S,T" or "MS,T" (the merge M(s,t)), as --isolate takes it;
// "mediumSampling" is "distance", "equiangular" or "mis" (the path tracer in media, --medium-sampling).
//
// Only "name" is required. A field left out takes the default of `pathlab view` (bpt, all,
// balance, beta 2, min connection 0.001, max length 10, no isolation), so a preset always means
// the same thing; the camera is kept as it is when the preset has none.
#pragma once

#include "core/render/render_settings.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab::ui {

class PresetError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct NamedPreset {
  std::string name;
  IntegratorKind integrator = IntegratorKind::Bpt;
  TechniqueSet techniques = TechniqueSet::all();
  MisOptions mis;
  int maxLength = 10;
  std::optional<Isolation> isolate;
  MergeSite mergeSite = MergeSite::Every;  // ppm: FirstNonSpecular
  std::optional<MediumSampling> mediumSampling;  // unset: the integrator's default
  std::optional<CameraDesc> camera;
  // Side B of the A/B comparison (a converge CONFIG, ui/lane/compare.h): the preset sets both sides and
  // turns the comparison on. None: the comparison is left as it is.
  std::optional<std::string> compare;

  // `current` with this preset's estimator state (and camera, if it has one); image size, seed,
  // lens and Russian roulette stay.
  RenderSettings applyTo(const RenderSettings& current) const;
};

// Throws PresetError with one line "PATH: problem" (preset index and name included) for unreadable
// files, malformed JSON, unknown keys or values, a SPEC that does not parse, an isolated technique
// longer than maxLength, duplicate names.
std::vector<NamedPreset> loadPresets(const std::string& path);
std::vector<NamedPreset> parsePresets(const std::string& json, const std::string& path);
// Throws PresetError naming the known presets when there is none called `name`.
const NamedPreset& findPreset(const std::vector<NamedPreset>& presets, const std::string& name,
                              const std::string& path);

// Camera looking from `eye` at `target` with world +y up; yfov in radians.
CameraDesc lookAtCamera(const Vec3& eye, const Vec3& target, float yfov);

}  // namespace pathlab::ui
