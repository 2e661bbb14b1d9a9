// One thread's light-tracing splats of one pass, added to the film when the pass ends: no atomic
// read-modify-write per splat (each was a compare-and-swap loop on three shared doubles, a few
// per cent of a bidirectional pass). Float is enough within a pass (a pixel receives a handful of
// splats); the film keeps the sums over passes in double.
#pragma once

#include "core/film/film.h"

#include <vector>

namespace pathlab {

class SplatBuffer {
 public:
  SplatBuffer(int width, int height);

  // The same door and the same pixel as Film::splat.
  bool splat(Vec2 pRaster, const Spectrum& v);
  // Asks the cache for the pixel a splat at pRaster will land in: a t = 1 connection knows it
  // before its shadow ray and weight, and the buffer is larger than the cache (a miss here was
  // most of the splat's cost).
  void prefetch(Vec2 pRaster) const {
    if (const std::optional<size_t> pixel = filmPixel(pRaster, width_, height_))
      __builtin_prefetch(&rgb_[3 * *pixel], 1);
  }
  // Adds this pass's splats to `film` (of the same size) and clears them.
  void mergeInto(Film& film);
  void clear();

  // Bytes one buffer of this size takes.
  static size_t bytesFor(int width, int height) {
    return 3 * sizeof(float) * static_cast<size_t>(width) * static_cast<size_t>(height);
  }

 private:
  int width_, height_;
  std::vector<float> rgb_;
  bool empty_ = true;
};

}  // namespace pathlab
