// The light-tracing splats of one pass summed in float, 3 a pixel, then added to the film's
// doubles when the pass ends: no atomic read-modify-write per splat (each was a compare-and-swap
// loop on three shared doubles, a few per cent of a bidirectional pass). Float is enough within a
// pass (a pixel receives a handful of splats); the film keeps the sums over passes in double.
//
// The render session adds the splats a work item at a time in a fixed order (pass_tiles.h), so
// each pixel's float sum is the same whatever thread rendered what. The buffer (12 bytes a pixel,
// 3 MiB at 512²) is larger than the cache and splats land anywhere on it, so adding each at once
// would stall on a cache miss (it was over 90 % of a splat's cost, and 7 % of a BPT sample): the
// pixels are prefetched a few splats ahead so that the misses overlap. Each pixel still receives
// its splats in their order, so the sums are bit for bit those of adding each splat at once.
#pragma once

#include "core/film/film.h"

#include <span>
#include <vector>

namespace pathlab {

class SplatSums {
 public:
  SplatSums(int width, int height);

  // Adds splats (pixels of this film's size) in their order.
  void add(std::span<const Splat> splats);
  // Adds the sums to `film` (of the same size) and clears them.
  void mergeInto(Film& film);
  void clear();

  // Bytes the sums of a film of this size take.
  static size_t bytesFor(int width, int height) {
    return 3 * sizeof(float) * static_cast<size_t>(width) * static_cast<size_t>(height);
  }

 private:
  std::vector<float> rgb_;
  bool empty_ = true;
};

}  // namespace pathlab
