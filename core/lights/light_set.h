// All emitters of a scene, chosen in proportion to their power (the environment's over the scene's
// bounding disk), the map from emissive triangles to their area lights, and the environment's index.
#pragma once

#include "core/lights/light.h"
#include "core/sampling/distribution1d.h"

#include <vector>

namespace pathlab {

class LightSet {
 public:
  LightSet() = default;
  // `triangleLight[mesh][prim]` is the index of the area light of that triangle, or -1.
  LightSet(std::vector<Light> lights, std::vector<std::vector<int>> triangleLight);

  size_t size() const { return lights_.size(); }
  bool empty() const { return lights_.empty(); }
  const Light& operator[](size_t i) const { return lights_[i]; }

  // Choose a light in proportion to power; returns its index and its probability, or -1 with
  // pmf 0 when no light has power.
  int sample(float u, float* pmf, float* uRemapped = nullptr) const;
  float pmf(int light) const { return static_cast<float>(distribution_.pmf(static_cast<size_t>(light))); }
  // The index of the environment light, -1 without one.
  int environment() const { return environment_; }
  int lightOfTriangle(uint32_t mesh, uint32_t prim) const {
    return mesh < triangleLight_.size() && prim < triangleLight_[mesh].size()
               ? triangleLight_[mesh][prim] : -1;
  }

 private:
  std::vector<Light> lights_;
  std::vector<std::vector<int>> triangleLight_;
  Distribution1D distribution_;
  int environment_ = -1;
};

}  // namespace pathlab
