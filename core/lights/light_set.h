// All emitters of a scene, chosen in proportion to their power (the environment's over the scene's
// bounding disk), the map from emissive triangles to their area lights, and the environment's index.
// Next-event estimation may instead choose by what each light can send to the receiving point (a
// light BVH, light_bvh.h): `sampleNee` / `pmfNee`. Light subpaths always choose by power.
#pragma once

#include "core/lights/light.h"
#include "core/lights/light_bvh.h"
#include "core/lights/light_selection.h"
#include "core/sampling/distribution1d.h"

#include <memory>
#include <vector>

namespace pathlab {


class LightSet {
 public:
  LightSet() = default;
  // `triangleLight[mesh][prim]` is the index of the area light of that triangle, or -1.
  // `emitters`: how many separate emitters the lights come from (an emissive mesh counts once),
  // for LightSelection::Auto.
  LightSet(std::vector<Light> lights, std::vector<std::vector<int>> triangleLight,
           LightSelection selection = LightSelection::Power, int emitters = 1);

  size_t size() const { return lights_.size(); }
  bool empty() const { return lights_.empty(); }
  const Light& operator[](size_t i) const { return lights_[i]; }

  // Choose a light in proportion to power; returns its index and its probability, or -1 with
  // pmf 0 when no light has power.
  int sample(float u, float* pmf, float* uRemapped = nullptr) const;
  float pmf(int light) const { return static_cast<float>(distribution_.pmf(static_cast<size_t>(light))); }

  // Next-event estimation's choice for a receiver at ctx and its probability (sample / pmf
  // without the BVH: then exactly those).
  int sampleNee(const LightSampleContext& ctx, float u, float* pmf) const {
    return bvh_ ? bvh_->sample(ctx, u, pmf) : sample(u, pmf);
  }
  float pmfNee(const LightSampleContext& ctx, int light) const { return bvh_ ? bvh_->pmf(ctx, light) : pmf(light); }
  // Whether pmfNee depends on the receiver (a BVH chooses): the MIS weights then tell the
  // next-event density of a path's light vertex from its density as a light subpath's origin.
  bool neeByContext() const { return bvh_ != nullptr; }
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
  std::shared_ptr<const LightBvh> bvh_;  // shared: LightSet is copied with the scene's other parts
};

}  // namespace pathlab
