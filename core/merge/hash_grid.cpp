// HashGrid::build: buckets computed, points sorted by (bucket, index) and bucket ranges found, all
// in parallel.
#include "core/merge/hash_grid.h"

#include "core/merge/room.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <stdexcept>

namespace pathlab {

void HashGrid::build(std::span<const Vec3> points, float radius) {
  if (!(radius > 0.f) || !std::isfinite(radius)) throw std::invalid_argument("HashGrid: the radius must be positive and finite");
  if (points.size() >= UINT32_MAX) throw std::invalid_argument("HashGrid: too many points");
  radius_ = radius;
  radius2_ = radius * radius;
  invCellSize_ = 1.f / (2.f * radius);
  const size_t n = points.size();
  bucketBits_ = 0;
  while ((uint64_t{1} << bucketBits_) < 2 * static_cast<uint64_t>(n)) ++bucketBits_;
  const size_t buckets = size_t{1} << bucketBits_;
  std::vector<uint64_t>& keys = keys_;  // bucket << 32 | index: sorting them sorts by (bucket, index)
  resizeWithRoom(keys, n);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      const Vec3 c = points[i] * invCellSize_;
      const uint64_t b = bucketOf(cellCoordinate(c.x), cellCoordinate(c.y), cellCoordinate(c.z));
      keys[i] = b << 32 | i;
    }
  });
  tbb::parallel_sort(keys.begin(), keys.end());
  resizeWithRoom(index_, n);
  resizeWithRoom(position_, n);
  assignWithRoom(range_, buckets, std::array<uint32_t, 2>{0u, 0u});
  // A bucket's range starts where its key first appears and ends after its last: each boundary is
  // written by the one thread that sees it, so the ranges need no atomics.
  tbb::parallel_for(tbb::blocked_range<size_t>(0, n), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t j = r.begin(); j != r.end(); ++j) {
      const uint32_t i = static_cast<uint32_t>(keys[j]);
      const uint64_t b = keys[j] >> 32;
      index_[j] = i;
      position_[j] = points[i];
      if (j == 0 || keys[j - 1] >> 32 != b) range_[b][0] = static_cast<uint32_t>(j);
      if (j + 1 == n || keys[j + 1] >> 32 != b) range_[b][1] = static_cast<uint32_t>(j + 1);
    }
  });
  // The occupancy bitmap, a word (64 buckets) per task item: each word written by one thread.
  const size_t words = (buckets + 63) / 64;
  assignWithRoom(occupied_, words, uint64_t{0});
  tbb::parallel_for(tbb::blocked_range<size_t>(0, words), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t w = r.begin(); w != r.end(); ++w) {
      uint64_t bits = 0;
      for (size_t k = 0; k < 64 && 64 * w + k < buckets; ++k)
        if (range_[64 * w + k][0] < range_[64 * w + k][1]) bits |= uint64_t{1} << k;
      occupied_[w] = bits;
    }
  });
}

}  // namespace pathlab
