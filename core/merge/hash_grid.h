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
#include <utility>
#include <vector>

namespace pathlab {

// Cells of side 2r, hashed into the power of two of buckets at or above twice the points. A ball
// of radius r lies within the 2 x 2 x 2 cells nearest its centre, so a query visits at most eight
// buckets; two of them may be one bucket (a hash collision), which is visited once. Points are kept
// sorted by (bucket, index) with their positions beside them, so a bucket's points are contiguous
// and the result does not depend on the thread count that built the grid. A bitmap of the occupied
// buckets (an eighth of a byte each, a cache-resident fraction of the ranges) lets a query skip the
// empty ones without reading their ranges: on a surface most cells of side 2r hold no light vertex
// when a pass keeps few of them (--noncaustic-photons), and at most 1 - e^(-1/2) of the buckets are
// occupied.
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
    querySlots(x, [&](uint32_t slot) { fn(index_[slot]); });
  }

  // The same by slot: the grid keeps its points sorted by (bucket, index), and slot j holds point
  // pointOfSlot(j). Data a caller lays out in slot order is read contiguously by a query, one
  // bucket after another (MergePass::records); prefetch(j) is called with the first slot of each
  // non-empty bucket before any fn, so the caller can prefetch its own data there.
  template <class Fn>
  void querySlots(const Vec3& x, Fn&& fn) const {
    querySlots(x, std::forward<Fn>(fn), [](uint32_t) {});
  }
  template <class Fn, class Prefetch>
  void querySlots(const Vec3& x, Fn&& fn, Prefetch&& prefetch) const {
    if (index_.empty()) return;
    std::array<uint32_t, 8> buckets;
    const size_t count = occupiedBucketsNear(x, buckets);
    if (count == 0) return;
    // The buckets lie far apart in a store of a million points, so each visit misses the caches
    // twice (its range, then its points): the misses are issued together first, so that they
    // overlap instead of following one another (the query's cost is memory latency, not work).
    for (size_t n = 0; n < count; ++n) __builtin_prefetch(&range_[buckets[n]]);
    std::array<std::array<uint32_t, 2>, 8> ranges;
    for (size_t n = 0; n < count; ++n) {
      ranges[n] = range_[buckets[n]];
      if (ranges[n][0] < ranges[n][1]) {
        __builtin_prefetch(&position_[ranges[n][0]]);
        prefetch(ranges[n][0]);
      }
    }
    for (size_t n = 0; n < count; ++n) {
      for (uint32_t j = ranges[n][0]; j < ranges[n][1]; ++j) {
        const Vec3 d = position_[j] - x;
        if (d.x * d.x + d.y * d.y + d.z * d.z <= radius2_) fn(j);
      }
    }
  }
  uint32_t pointOfSlot(uint32_t slot) const { return index_[slot]; }

 private:
  // The distinct occupied buckets of the 2 x 2 x 2 cells nearest x, ascending; returns their count.
  size_t occupiedBucketsNear(const Vec3& x, std::array<uint32_t, 8>& buckets) const {
    const Vec3 c = x * invCellSize_;
    // Per axis, the cell holding x and the neighbour on the side x is closer to.
    const int64_t base[3] = {cellCoordinate(c.x), cellCoordinate(c.y), cellCoordinate(c.z)};
    const int64_t step[3] = {c.x - std::floor(c.x) < 0.5f ? -1 : 1, c.y - std::floor(c.y) < 0.5f ? -1 : 1,
                             c.z - std::floor(c.z) < 0.5f ? -1 : 1};
    size_t count = 0;
    for (int n = 0; n < 8; ++n) {
      const uint32_t b =
          bucketOf(base[0] + (n & 1 ? step[0] : 0), base[1] + (n & 2 ? step[1] : 0), base[2] + (n & 4 ? step[2] : 0));
      if (!(occupied_[b >> 6] >> (b & 63) & 1u)) continue;
      // Insertion into the ascending list, once (the few occupied ones: usually none to three).
      size_t at = count;
      while (at > 0 && buckets[at - 1] > b) --at;
      if (at > 0 && buckets[at - 1] == b) continue;
      for (size_t m = count; m > at; --m) buckets[m] = buckets[m - 1];
      buckets[at] = b;
      ++count;
    }
    return count;
  }
  // Cell coordinates clamped far beyond any scene (2^40 cells of side 2r), so huge or infinite
  // coordinates still hash and a query never overflows.
  static int64_t cellCoordinate(float c) {
    constexpr float kLimit = 1099511627776.f;  // 2^40
    return static_cast<int64_t>(std::floor(std::clamp(c, -kLimit, kLimit)));
  }
  uint32_t bucketOf(int64_t x, int64_t y, int64_t z) const {
    // Teschner et al. 2003's spatial hash (large primes, xor), over 64-bit coordinates, then its
    // high bits by a Fibonacci multiply (Knuth): the low bits alone would repeat with the cells'.
    const uint64_t h = (static_cast<uint64_t>(x) * 73856093u) ^ (static_cast<uint64_t>(y) * 19349663u) ^
                       (static_cast<uint64_t>(z) * 83492791u);
    return bucketBits_ == 0 ? 0u : static_cast<uint32_t>((h * 0x9E3779B97F4A7C15ull) >> (64 - bucketBits_));
  }

  float radius_ = 0.f, radius2_ = 0.f, invCellSize_ = 0.f;
  int bucketBits_ = 0;                 // 2^bucketBits_ buckets
  std::vector<uint64_t> occupied_;     // a bit per bucket: any point in it
  // Per bucket: its points' range [begin, end) in index_ and position_ (one array: a query's
  // visit to a bucket reads one cache line for it).
  std::vector<std::array<uint32_t, 2>> range_;
  std::vector<uint32_t> index_;        // point indices sorted by (bucket, index)
  std::vector<Vec3> position_;         // their positions, in the same order
  std::vector<uint64_t> keys_;         // build's scratch, kept between builds
};

}  // namespace pathlab
