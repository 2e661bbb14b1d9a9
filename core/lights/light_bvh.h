// Context-dependent light selection for next-event estimation: a BVH over the lights with a
// position, descended by the importance each child's bounds give the receiving point (Conty
// Estevez and Kulla 2018; pbrt-v4 BVHLightSampler), and the lights at infinity weighed against
// the whole tree by their irradiance scale. Both the sampling and the exact probability of any
// light for a given receiver, which the MIS weights of every technique need (mis.cpp).
#pragma once

#include "core/lights/light.h"

#include <vector>

namespace pathlab {

class LightBvh {
 public:
  LightBvh() = default;
  // Lights of zero power are left out (probability zero), as LightSet's power distribution does.
  explicit LightBvh(const std::vector<Light>& lights);

  // A light for a receiver at ctx and its probability; -1 with pmf 0 when none can light it.
  int sample(const LightSampleContext& ctx, float u, float* pmf) const;
  // The probability sample() gives `light` at ctx (the same products, in the same order).
  float pmf(const LightSampleContext& ctx, int light) const;

  size_t nodeCount() const { return nodes_.size(); }

 private:
  struct Node {
    LightBounds bounds;
    int child0 = -1;  // interior: children child0 and child0 + 1; leaf: -1
    int light = -1;   // leaf: the light's index in the set
    int parent = -1;
  };
  // Fills node `index` (already allocated) with the lights items[begin, end).
  void build(std::vector<std::pair<int, LightBounds>>& items, size_t begin, size_t end, int parent, int depth, int index);
  // The probability of descending into child0 rather than child0 + 1 of interior node `node`.
  float shareOfFirst(const Node& node, const LightSampleContext& ctx) const;
  // The probability of choosing the tree rather than a light at infinity.
  float treeShare(const LightSampleContext& ctx, float* infiniteTotal) const;

  std::vector<Node> nodes_;
  std::vector<int> leafOfLight_;      // node index per light, -1 when not in the tree
  std::vector<int> infinite_;          // lights at infinity with importance
  std::vector<float> infiniteWeight_;  // their infiniteImportance()
  std::vector<int> infiniteSlot_;      // per light: index in infinite_, or -1
  float infiniteTotal_ = 0.f;          // the sum of infiniteWeight_
};

}  // namespace pathlab
