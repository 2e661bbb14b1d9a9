// SplatBuffer: per-thread splat sums of a pass.
#include "core/film/splat_buffer.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

SplatBuffer::SplatBuffer(int width, int height)
    : width_(width), height_(height), rgb_(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f) {}

bool SplatBuffer::splat(Vec2 pRaster, const Spectrum& v) {
  if (!isValidContribution(v)) return false;
  const std::optional<size_t> pixel = filmPixel(pRaster, width_, height_);
  if (!pixel) return true;  // off the film: no pixel measures it
  float* rgb = &rgb_[3 * *pixel];
  rgb[0] += v.r;
  rgb[1] += v.g;
  rgb[2] += v.b;
  empty_ = false;
  return true;
}

void SplatBuffer::mergeInto(Film& film) {
  if (empty_) return;
  film.addSplatSums(rgb_);
  clear();
}

void SplatBuffer::clear() {
  if (!empty_) std::fill(rgb_.begin(), rgb_.end(), 0.f);
  empty_ = true;
}

}  // namespace pathlab
