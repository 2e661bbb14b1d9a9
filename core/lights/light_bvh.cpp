// LightBvh: a binned build minimising Conty and Kulla's cost (power x orientation measure x
// surface area, sec. 4.3), one light per leaf, and the descent by child importance.
#include "core/lights/light_bvh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace pathlab {

namespace {

constexpr int kBuckets = 12;
// Past this depth the build splits at the median, so no path from the root is longer than
// kMedianDepth + log2(lights) (the pmf walks it on a fixed-size stack).
constexpr int kMedianDepth = 48;
constexpr int kMaxDepth = 128;

float surfaceArea(const LightBounds& b) {
  const Vec3 d = b.hi - b.lo;
  return 2.f * (d.x * d.y + d.y * d.z + d.z * d.x);
}

// Conty and Kulla eq. 1 with pbrt-v4's regularisation of thin boxes (Kr) and a floor for points.
float cost(const LightBounds& b, const LightBounds& parent, int axis) {
  const Vec3 d = parent.hi - parent.lo;
  const float maxExtent = std::max({d.x, d.y, d.z});
  const float kr = d[axis] > 0.f ? maxExtent / d[axis] : 1.f;
  return b.phi * orientationMeasure(b) * kr * std::max(surfaceArea(b), 1e-12f);
}

// The centroid bucket (of kBuckets over [lo, lo + extent] on `axis`) a light's bounds fall in.
int bucketOf(const LightBounds& b, int axis, float lo, float extent) {
  const int k = static_cast<int>(kBuckets * ((b.centroid()[axis] - lo) / extent));
  return std::clamp(k, 0, kBuckets - 1);
}

}  // namespace

LightBvh::LightBvh(const std::vector<Light>& lights) {
  std::vector<std::pair<int, LightBounds>> items;
  leafOfLight_.assign(lights.size(), -1);
  infiniteSlot_.assign(lights.size(), -1);
  for (size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].isInfinite()) {
      const float w = lights[i].infiniteImportance();
      if (!(w > 0.f) || !std::isfinite(w)) continue;
      infiniteSlot_[i] = static_cast<int>(infinite_.size());
      infinite_.push_back(static_cast<int>(i));
      infiniteWeight_.push_back(w);
      continue;
    }
    const LightBounds b = lights[i].lightBounds();
    if (b.phi > 0.f) items.emplace_back(static_cast<int>(i), b);
  }
  for (const float w : infiniteWeight_) infiniteTotal_ += w;
  if (items.empty()) return;
  nodes_.reserve(2 * items.size());
  nodes_.push_back(Node{});
  build(items, 0, items.size(), -1, 0, 0);
}

void LightBvh::build(std::vector<std::pair<int, LightBounds>>& items, size_t begin, size_t end, int parent, int depth,
                     int index) {
  nodes_[static_cast<size_t>(index)].parent = parent;
  if (end - begin == 1) {
    nodes_[static_cast<size_t>(index)].bounds = items[begin].second;
    nodes_[static_cast<size_t>(index)].light = items[begin].first;
    leafOfLight_[static_cast<size_t>(items[begin].first)] = index;
    return;
  }
  LightBounds all;
  Vec3 cLo(std::numeric_limits<float>::max()), cHi(-std::numeric_limits<float>::max());
  for (size_t i = begin; i < end; ++i) {
    all = unionOf(all, items[i].second);
    cLo = glm::min(cLo, items[i].second.centroid());
    cHi = glm::max(cHi, items[i].second.centroid());
  }

  // The cheapest split over kBuckets centroid buckets on each axis.
  size_t mid = begin + (end - begin) / 2;
  float bestCost = std::numeric_limits<float>::infinity();
  int bestAxis = -1, bestBucket = -1;
  if (depth < kMedianDepth)
    for (int axis = 0; axis < 3; ++axis) {
      const float extent = cHi[axis] - cLo[axis];
      if (!(extent > 0.f)) continue;
      std::array<LightBounds, kBuckets> buckets{};
      for (size_t i = begin; i < end; ++i) {
        LightBounds& bucket = buckets[static_cast<size_t>(bucketOf(items[i].second, axis, cLo[axis], extent))];
        bucket = unionOf(bucket, items[i].second);
      }
      for (int split = 0; split + 1 < kBuckets; ++split) {
        LightBounds below, above;
        for (int k = 0; k <= split; ++k) below = unionOf(below, buckets[static_cast<size_t>(k)]);
        for (int k = split + 1; k < kBuckets; ++k) above = unionOf(above, buckets[static_cast<size_t>(k)]);
        if (!(below.phi > 0.f) || !(above.phi > 0.f)) continue;
        const float c = cost(below, all, axis) + cost(above, all, axis);
        if (c < bestCost) bestCost = c, bestAxis = axis, bestBucket = split;
      }
    }
  if (bestAxis >= 0) {
    const float extent = cHi[bestAxis] - cLo[bestAxis];
    auto below = [&](const std::pair<int, LightBounds>& item) {
      return bucketOf(item.second, bestAxis, cLo[bestAxis], extent) <= bestBucket;
    };
    mid = static_cast<size_t>(std::partition(items.begin() + static_cast<std::ptrdiff_t>(begin),
                                             items.begin() + static_cast<std::ptrdiff_t>(end), below) -
                              items.begin());
  }
  if (bestAxis < 0 || mid == begin || mid == end) {
    // No bucket split: the median along the widest centroid axis.
    const Vec3 extent = cHi - cLo;
    const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
    mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + static_cast<std::ptrdiff_t>(begin), items.begin() + static_cast<std::ptrdiff_t>(mid),
                     items.begin() + static_cast<std::ptrdiff_t>(end), [axis](const auto& a, const auto& b) {
                       return a.second.centroid()[axis] < b.second.centroid()[axis];
                     });
  }
  // Both children sit next to each other: child0 and child0 + 1.
  const int child0 = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_.push_back(Node{});
  nodes_[static_cast<size_t>(index)].child0 = child0;
  nodes_[static_cast<size_t>(index)].bounds = all;
  build(items, begin, mid, index, depth + 1, child0);
  build(items, mid, end, index, depth + 1, child0 + 1);
}

float LightBvh::shareOfFirst(const Node& node, const LightSampleContext& ctx) const {
  const double c0 = nodes_[static_cast<size_t>(node.child0)].bounds.importance(ctx);
  const double c1 = nodes_[static_cast<size_t>(node.child0) + 1].bounds.importance(ctx);
  if (!(c0 + c1 > 0.0)) return -1.f;  // nothing below can light ctx
  return static_cast<float>(c0 / (c0 + c1));
}

float LightBvh::treeShare(const LightSampleContext& ctx, float* infiniteTotal) const {
  const float infinite = infiniteTotal_;
  *infiniteTotal = infinite;
  const float tree = nodes_.empty() ? 0.f : nodes_[0].bounds.importance(ctx);
  const float total = infinite + tree;
  if (!(total > 0.f)) return -1.f;
  return tree / total;
}

int LightBvh::sample(const LightSampleContext& ctx, float u, float* pmf) const {
  *pmf = 0.f;
  float infinite = 0.f;
  const float pTree = treeShare(ctx, &infinite);
  if (pTree < 0.f) return -1;
  const float pInfinite = 1.f - pTree;
  if (u < pInfinite || nodes_.empty()) {
    // A light at infinity, in proportion to its weight: the same quotient pmf() forms.
    const float target = u / pInfinite * infinite;
    float cumulative = 0.f;
    for (size_t i = 0; i < infinite_.size(); ++i) {
      cumulative += infiniteWeight_[i];
      if (target < cumulative || i + 1 == infinite_.size()) {
        *pmf = pInfinite * (infiniteWeight_[i] / infinite);  // as pmf() forms it
        return infinite_[i];
      }
    }
    return -1;
  }
  u = std::min((u - pInfinite) / pTree, kOneMinusEpsilon);
  float p = pTree;
  int node = 0;
  while (nodes_[static_cast<size_t>(node)].child0 >= 0) {
    const Node& n = nodes_[static_cast<size_t>(node)];
    const float p0 = shareOfFirst(n, ctx);
    if (p0 < 0.f) return -1;
    if (u < p0) {
      u = std::min(u / p0, kOneMinusEpsilon);
      p *= p0;
      node = n.child0;
    } else {
      u = std::min((u - p0) / (1.f - p0), kOneMinusEpsilon);
      p *= 1.f - p0;
      node = n.child0 + 1;
    }
  }
  *pmf = p;
  return nodes_[static_cast<size_t>(node)].light;
}

float LightBvh::pmf(const LightSampleContext& ctx, int light) const {
  if (light < 0 || static_cast<size_t>(light) >= leafOfLight_.size()) return 0.f;
  float infinite = 0.f;
  const float pTree = treeShare(ctx, &infinite);
  if (pTree < 0.f) return 0.f;
  // The probability sample() chooses it with: the share of the lights at infinity (which may
  // round to zero beside a very bright emitter), then its weight among them.
  if (const int slot = infiniteSlot_[static_cast<size_t>(light)]; slot >= 0)
    return (1.f - pTree) * (infiniteWeight_[static_cast<size_t>(slot)] / infinite);
  const int leaf = leafOfLight_[static_cast<size_t>(light)];
  if (leaf < 0) return 0.f;
  // The path from the root, walked down as sample() walks it (the same products in the same order).
  std::array<int, kMaxDepth + 1> path{};
  int length = 0;
  for (int node = leaf; node >= 0 && length <= kMaxDepth; node = nodes_[static_cast<size_t>(node)].parent)
    path[static_cast<size_t>(length++)] = node;
  float p = pTree;
  for (int k = length - 1; k >= 1; --k) {
    const Node& n = nodes_[static_cast<size_t>(path[static_cast<size_t>(k)])];
    const float p0 = shareOfFirst(n, ctx);
    if (p0 < 0.f) return 0.f;
    p *= path[static_cast<size_t>(k - 1)] == n.child0 ? p0 : 1.f - p0;
  }
  return p;
}

}  // namespace pathlab
