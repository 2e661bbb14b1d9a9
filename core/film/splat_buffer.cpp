// SplatBuffer: per-thread splat sums of a pass.
#include "core/film/splat_buffer.h"

#include <algorithm>

namespace pathlab {

SplatBuffer::SplatBuffer(int width, int height)
    : width_(width), height_(height), rgb_(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f) {}

void SplatBuffer::addPending() {
  // How far ahead to prefetch: enough misses in flight to hide the memory latency (about eight
  // splats' worth of adds), few enough that the prefetched lines are still there when used.
  constexpr int kAhead = 8;
  const int n = pendingCount_;
  for (int i = 0; i < std::min(n, kAhead); ++i) __builtin_prefetch(&rgb_[3 * size_t(pending_[i].pixel)], 1);
  for (int i = 0; i < n; ++i) {
    if (i + kAhead < n) __builtin_prefetch(&rgb_[3 * size_t(pending_[i + kAhead].pixel)], 1);
    const Pending& p = pending_[i];
    float* rgb = &rgb_[3 * size_t(p.pixel)];
    rgb[0] += p.v.r;
    rgb[1] += p.v.g;
    rgb[2] += p.v.b;
  }
  if (n > 0) empty_ = false;
  pendingCount_ = 0;
}

void SplatBuffer::mergeInto(Film& film) {
  addPending();
  if (empty_) return;
  film.addSplatSums(rgb_);
  clear();
}

void SplatBuffer::clear() {
  pendingCount_ = 0;
  if (!empty_) std::fill(rgb_.begin(), rgb_.end(), 0.f);
  empty_ = true;
}

}  // namespace pathlab
