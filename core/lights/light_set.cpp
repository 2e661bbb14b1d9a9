// LightSet: power-proportional light selection and the emissive-triangle map.
#include "core/lights/light_set.h"

#include <cmath>

namespace pathlab {

LightSet::LightSet(std::vector<Light> lights, std::vector<std::vector<int>> triangleLight, LightSelection selection,
                   int emitters)
    : lights_(std::move(lights)), triangleLight_(std::move(triangleLight)) {
  std::vector<double> weights;
  weights.reserve(lights_.size());
  for (const Light& l : lights_) {
    if (l.type() == LightType::Environment) environment_ = static_cast<int>(weights.size());
    const double w = luminance(l.power());
    // A light with zero (or non-finite) power is never chosen.
    weights.push_back(std::isfinite(w) && w > 0.0 ? w : 0.0);
  }
  distribution_ = Distribution1D(weights);
  // One emitter (the Cornell box's ceiling light): where it is bright enough to matter, every
  // part of it is; the BVH would cost each connection its descent for little. A scene pays for it
  // only when it has lights to tell apart.
  const bool useBvh = selection == LightSelection::Bvh || (selection == LightSelection::Auto && emitters > 1);
  if (useBvh && !lights_.empty()) bvh_ = std::make_shared<const LightBvh>(lights_);
}

int LightSet::sample(float u, float* pmf, float* uRemapped) const {
  if (lights_.empty() || !(distribution_.total() > 0.0)) {
    if (pmf) *pmf = 0.f;
    if (uRemapped) *uRemapped = 0.f;
    return -1;
  }
  return static_cast<int>(distribution_.sample(u, pmf, uRemapped));
}

}  // namespace pathlab
