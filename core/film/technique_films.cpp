// Per-technique accumulation buffers.
#include "core/film/technique_films.h"

#include <atomic>
#include <cmath>

namespace pathlab {

uint64_t TechniqueFilms::bytesFor(int width, int height, int maxLength) {
  return 2 * Technique::countUpTo(maxLength) * 3 * sizeof(double) * static_cast<uint64_t>(width) *
         static_cast<uint64_t>(height);
}

TechniqueFilms::TechniqueFilms(int width, int height, int maxLength)
    : width_(width), height_(height), maxLength_(maxLength) {
  const size_t values = 3 * static_cast<size_t>(width) * static_cast<size_t>(height);
  buffers_.assign(2 * Technique::countUpTo(maxLength), std::vector<double>(values, 0.0));
}

size_t TechniqueFilms::buffer(int s, int t, bool unweighted) const {
  return 2 * Technique{s, t}.index() + (unweighted ? 1 : 0);
}

void TechniqueFilms::add(int s, int t, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted) {
  if (!covers(s, t)) return;
  const int x = static_cast<int>(std::floor(pRaster.x)), y = static_cast<int>(std::floor(pRaster.y));
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x));
  std::vector<double>& w = buffers_[buffer(s, t, false)];
  std::vector<double>& u = buffers_[buffer(s, t, true)];
  for (int c = 0; c < 3; ++c) {
    const size_t j = i + static_cast<size_t>(c);
    if (t == 1) {
      std::atomic_ref<double>(w[j]).fetch_add(weighted[c], std::memory_order_relaxed);
      std::atomic_ref<double>(u[j]).fetch_add(unweighted[c], std::memory_order_relaxed);
    } else {
      w[j] += weighted[c];
      u[j] += unweighted[c];
    }
  }
}

void TechniqueFilms::clear() {
  for (std::vector<double>& b : buffers_) std::fill(b.begin(), b.end(), 0.0);
}

Image TechniqueFilms::readout(int s, int t, bool unweighted, uint64_t samplesPerPixel, uint64_t lightSubpaths) const {
  Image img{width_, height_, std::vector<float>(3 * static_cast<size_t>(width_) * static_cast<size_t>(height_), 0.f)};
  if (!covers(s, t)) return img;
  const double pixels = static_cast<double>(width_) * static_cast<double>(height_);
  const double scale = t == 1 ? (lightSubpaths ? pixels / static_cast<double>(lightSubpaths) : 0.0)
                              : (samplesPerPixel ? 1.0 / static_cast<double>(samplesPerPixel) : 0.0);
  const std::vector<double>& b = buffers_[buffer(s, t, unweighted)];
  for (size_t i = 0; i < b.size(); ++i) img.rgb[i] = static_cast<float>(b[i] * scale);
  return img;
}

}  // namespace pathlab
