// Film accumulation and read-out.
#include "core/film/film.h"

namespace pathlab {

Film::Film(int width, int height)
    : width_(width), height_(height), cameraSum_(pixelCount(), DVec3(0.0)), splatSum_(3 * pixelCount(), 0.0) {}

bool Film::addSample(int x, int y, const Spectrum& L) {
  if (!isValidContribution(L)) return false;
  cameraSum_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)] += DVec3(L);
  return true;
}

bool Film::addCorrection(int x, int y, const Spectrum& c) {
  if (!isFinite(c)) return false;
  cameraSum_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)] += DVec3(c);
  return true;
}

void Film::addCorrections(std::vector<DVec3>& perPixel) {
  for (size_t p = 0; p < perPixel.size() && p < cameraSum_.size(); ++p) {
    if (std::isfinite(perPixel[p].x) && std::isfinite(perPixel[p].y) && std::isfinite(perPixel[p].z)) cameraSum_[p] += perPixel[p];
    perPixel[p] = DVec3(0.0);
  }
}

bool Film::splat(Vec2 pRaster, const Spectrum& v) {
  if (!isValidContribution(v)) return false;
  const std::optional<size_t> pixel = filmPixel(pRaster, width_, height_);
  if (!pixel) return true;  // off the film: no pixel measures it
  const size_t i = 3 * *pixel;
  for (int c = 0; c < 3; ++c) std::atomic_ref<double>(splatSum_[i + static_cast<size_t>(c)]).fetch_add(v[c], std::memory_order_relaxed);
  return true;
}

void Film::addSplatSums(const std::vector<float>& rgb) {
  for (size_t i = 0; i < splatSum_.size() && i < rgb.size(); ++i) splatSum_[i] += static_cast<double>(rgb[i]);
}

void Film::addSplats(std::span<const Splat> splats) {
  for (const Splat& s : splats)
    for (int c = 0; c < 3; ++c) splatSum_[3 * size_t(s.pixel) + static_cast<size_t>(c)] += s.v[c];
}

std::array<std::span<double>, 2> Film::sums() {
  static_assert(sizeof(DVec3) == 3 * sizeof(double), "DVec3 must be three packed doubles");
  return {std::span<double>(reinterpret_cast<double*>(cameraSum_.data()), 3 * cameraSum_.size()),
          std::span<double>(splatSum_)};
}

std::array<std::span<const double>, 2> Film::sums() const {
  return {std::span<const double>(reinterpret_cast<const double*>(cameraSum_.data()), 3 * cameraSum_.size()),
          std::span<const double>(splatSum_)};
}

void Film::finishPass(uint64_t samplesPerPixel, uint64_t lightSubpaths) {
  samplesPerPixel_ += samplesPerPixel;
  lightSubpaths_ += lightSubpaths;
}

void Film::clear() {
  std::fill(cameraSum_.begin(), cameraSum_.end(), DVec3(0.0));
  std::fill(splatSum_.begin(), splatSum_.end(), 0.0);
  samplesPerPixel_ = 0;
  lightSubpaths_ = 0;
}

Image Film::readout() const {
  Image img{width_, height_, std::vector<float>(3 * pixelCount(), 0.f)};
  const double cameraScale = samplesPerPixel_ ? 1.0 / static_cast<double>(samplesPerPixel_) : 0.0;
  const double splatScale =
      lightSubpaths_ ? static_cast<double>(pixelCount()) / static_cast<double>(lightSubpaths_) : 0.0;
  for (size_t p = 0; p < pixelCount(); ++p)
    for (int c = 0; c < 3; ++c) {
      const size_t i = 3 * p + static_cast<size_t>(c);
      img.rgb[i] = static_cast<float>(cameraSum_[p][c] * cameraScale + splatSum_[i] * splatScale);
    }
  return img;
}

}  // namespace pathlab
