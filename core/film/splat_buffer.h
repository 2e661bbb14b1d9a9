// One thread's light-tracing splats of one pass, added to the film when the pass ends: no atomic
// read-modify-write per splat (each was a compare-and-swap loop on three shared doubles, a few
// per cent of a bidirectional pass). Float is enough within a pass (a pixel receives a handful of
// splats); the film keeps the sums over passes in double.
//
// The buffer (12 bytes a pixel, 3 MiB at 512²) is larger than the cache and t = 1 connections land
// anywhere on it, so adding a splat at once stalls on a cache miss (it was over 90 % of the
// splat's cost, and 7 % of a BPT sample). Splats are therefore queued in arrival order and added
// a block at a time, each pixel prefetched a few splats ahead: the misses overlap instead of
// following each other. Each pixel still receives its splats in the same order, so the sums are
// bit for bit those of adding each splat at once.
#pragma once

#include "core/film/film.h"

#include <array>
#include <cstdint>
#include <vector>

namespace pathlab {

class SplatBuffer {
 public:
  SplatBuffer(int width, int height);

  // The same door and the same pixel as Film::splat.
  bool splat(Vec2 pRaster, const Spectrum& v) {
    if (!isValidContribution(v)) return false;
    const std::optional<size_t> pixel = filmPixel(pRaster, width_, height_);
    if (!pixel) return true;  // off the film: no pixel measures it
    pending_[pendingCount_++] = Pending{static_cast<uint32_t>(*pixel), v};
    if (pendingCount_ == kBlock) addPending();
    return true;
  }
  // Adds this pass's splats to `film` (of the same size) and clears them.
  void mergeInto(Film& film);
  void clear();

  // Bytes one buffer of this size takes.
  static size_t bytesFor(int width, int height) {
    return 3 * sizeof(float) * static_cast<size_t>(width) * static_cast<size_t>(height) + sizeof(pending_);
  }

 private:
  struct Pending {
    uint32_t pixel;
    Spectrum v;
  };
  // A block small enough to stay in the first-level cache (16 KiB).
  static constexpr int kBlock = 1024;
  void addPending();

  int width_, height_;
  std::vector<float> rgb_;
  std::array<Pending, kBlock> pending_;
  int pendingCount_ = 0;
  bool empty_ = true;
};

}  // namespace pathlab
