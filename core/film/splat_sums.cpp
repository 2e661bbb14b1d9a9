// SplatSums: one pass's splats summed in float, in their order, the pixels prefetched ahead.
#include "core/film/splat_sums.h"

#include <algorithm>

namespace pathlab {

SplatSums::SplatSums(int width, int height) : rgb_(bytesFor(width, height) / sizeof(float), 0.f) {}

void SplatSums::add(std::span<const Splat> splats) {
  // How far ahead to prefetch: enough misses in flight to hide the memory latency (about eight
  // splats' worth of adds), few enough that the prefetched lines are still there when used.
  constexpr size_t kAhead = 8;
  const size_t n = splats.size();
  for (size_t i = 0; i < std::min(n, kAhead); ++i) __builtin_prefetch(&rgb_[3 * size_t(splats[i].pixel)], 1);
  for (size_t i = 0; i < n; ++i) {
    if (i + kAhead < n) __builtin_prefetch(&rgb_[3 * size_t(splats[i + kAhead].pixel)], 1);
    const Splat& s = splats[i];
    float* rgb = &rgb_[3 * size_t(s.pixel)];
    rgb[0] += s.v.r;
    rgb[1] += s.v.g;
    rgb[2] += s.v.b;
  }
  if (n > 0) empty_ = false;
}

void SplatSums::mergeInto(Film& film) {
  if (empty_) return;
  film.addSplatSums(rgb_);
  clear();
}

void SplatSums::clear() {
  if (!empty_) std::fill(rgb_.begin(), rgb_.end(), 0.f);
  empty_ = true;
}

}  // namespace pathlab
