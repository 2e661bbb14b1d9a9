// A hash grid for fixed-radius range search over the light vertices of a pass: vertex merging
// (Georgiev et al. 2012, sec. 5; Hachisuka and Jensen 2009's hashed grid) asks, for each camera
// vertex x, every light vertex within r of x.
#pragma once

#include "core/math/types.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace pathlab {

// Cells of side 2r, hashed into as many buckets as points (at least one). A ball of radius r lies
// within the 2 x 2 x 2 cells nearest its centre, so a query visits at most eight buckets; two of
// them may be one bucket (a hash collision), which is visited once. Points are kept sorted by
// (bucket, index) with their positions beside them, so a bucket's points are contiguous and the
// result does not depend on the thread count that built the grid.
class HashGrid {
 public:
  // Builds over `points` with radius r > 0 (finite). In parallel (TBB), no serial pass over the
  // points or the buckets.
  void build(std::span<const Vec3> points, float radius);

  float radius() const { return radius_; }
  size_t size() const { return index_.size(); }

  // Calls fn(i) for every point i (an index into build's span) with |points[i] - x| <= r, each
  // once, in ascending order of (bucket, i).
  template <class Fn>
  void query(const Vec3& x, Fn&& fn) const {
    if (index_.empty()) return;
    const Vec3 c = x * invCellSize_;
    // Per axis, the cell holding x and the neighbour on the side x is closer to.
    std::array<uint32_t, 8> buckets;
    const int64_t base[3] = {cellCoordinate(c.x), cellCoordinate(c.y), cellCoordinate(c.z)};
    const int64_t step[3] = {c.x - std::floor(c.x) < 0.5f ? -1 : 1, c.y - std::floor(c.y) < 0.5f ? -1 : 1,
                             c.z - std::floor(c.z) < 0.5f ? -1 : 1};
    for (int n = 0; n < 8; ++n)
      buckets[static_cast<size_t>(n)] =
          bucketOf(base[0] + (n & 1 ? step[0] : 0), base[1] + (n & 2 ? step[1] : 0), base[2] + (n & 4 ? step[2] : 0));
    std::sort(buckets.begin(), buckets.end());
    const auto last = std::unique(buckets.begin(), buckets.end());
    for (auto b = buckets.begin(); b != last; ++b) {
      for (uint32_t j = begin_[*b], end = end_[*b]; j < end; ++j) {
        const Vec3 d = position_[j] - x;
        if (d.x * d.x + d.y * d.y + d.z * d.z <= radius2_) fn(index_[j]);
      }
    }
  }

 private:
  // Cell coordinates clamped far beyond any scene (2^40 cells of side 2r), so huge or infinite
  // coordinates still hash and a query never overflows.
  static int64_t cellCoordinate(float c) {
    constexpr float kLimit = 1099511627776.f;  // 2^40
    return static_cast<int64_t>(std::floor(std::clamp(c, -kLimit, kLimit)));
  }
  uint32_t bucketOf(int64_t x, int64_t y, int64_t z) const {
    // Teschner et al. 2003's spatial hash (large primes, xor), over 64-bit coordinates.
    const uint64_t h = (static_cast<uint64_t>(x) * 73856093u) ^ (static_cast<uint64_t>(y) * 19349663u) ^
                       (static_cast<uint64_t>(z) * 83492791u);
    return static_cast<uint32_t>(h % buckets_);
  }

  float radius_ = 0.f, radius2_ = 0.f, invCellSize_ = 0.f;
  uint64_t buckets_ = 1;
  std::vector<uint32_t> begin_, end_;  // per bucket: its points' range in index_ and position_
  std::vector<uint32_t> index_;        // point indices sorted by (bucket, index)
  std::vector<Vec3> position_;         // their positions, in the same order
};

}  // namespace pathlab
