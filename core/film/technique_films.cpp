// Per-technique accumulation buffers.
#include "core/film/technique_films.h"

#include <algorithm>
#include <atomic>
#include <cmath>

namespace pathlab {

uint64_t TechniqueFilms::bytesFor(int width, int height, int maxLength, bool sampleable, TechniqueFamilies families,
                                  bool moments) {
  const uint64_t valuesPerPixel = 2 * 3 + (sampleable ? 2 : 0) + (moments ? 2 : 0);
  return Technique::countUpTo(maxLength, families) * valuesPerPixel * sizeof(double) * static_cast<uint64_t>(width) *
         static_cast<uint64_t>(height);
}

TechniqueFilms::TechniqueFilms(int width, int height, int maxLength, bool sampleable, TechniqueFamilies families,
                               bool moments)
    : width_(width), height_(height), maxLength_(maxLength), families_(families) {
  const size_t pixels = static_cast<size_t>(width) * static_cast<size_t>(height);
  buffers_.resize(2 * Technique::countUpTo(maxLength));
  if (sampleable) sampleable_.resize(2 * Technique::countUpTo(maxLength));
  if (moments) passEstimate_.resize(Technique::countUpTo(maxLength)), moments_.resize(Technique::countUpTo(maxLength));
  for (const Technique x : techniquesUpTo(maxLength, families)) {
    for (const bool second : {false, true}) {
      buffers_[buffer(x, second)].assign(3 * pixels, 0.0);
      if (sampleable) sampleable_[buffer(x, second)].assign(pixels, 0.0);
    }
    if (moments) passEstimate_[x.index()].assign(pixels, 0.0), moments_[x.index()].assign(pixels, 0.0);
  }
}

long long TechniqueFilms::pixel(Vec2 pRaster) const {
  const int x = static_cast<int>(std::floor(pRaster.x)), y = static_cast<int>(std::floor(pRaster.y));
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return -1;
  return static_cast<long long>(y) * width_ + x;
}

void TechniqueFilms::add(Technique x, Vec2 pRaster, const Spectrum& weighted, const Spectrum& unweighted) {
  if (!covers(x)) return;
  const long long p = pixel(pRaster);
  if (p < 0) return;
  const size_t i = 3 * static_cast<size_t>(p);
  std::vector<double>& w = buffers_[buffer(x, false)];
  std::vector<double>& u = buffers_[buffer(x, true)];
  const bool splat = x.t == 1 && !x.isMerge();
  for (int c = 0; c < 3; ++c) {
    const size_t j = i + static_cast<size_t>(c);
    if (splat) {
      std::atomic_ref<double>(w[j]).fetch_add(weighted[c], std::memory_order_relaxed);
      std::atomic_ref<double>(u[j]).fetch_add(unweighted[c], std::memory_order_relaxed);
    } else {
      w[j] += weighted[c];
      u[j] += unweighted[c];
    }
  }
  if (moments_.empty()) return;
  // This pass's estimate of the pixel by x (a merge may add several contributions a sample).
  double& e = passEstimate_[x.index()][static_cast<size_t>(p)];
  if (splat) std::atomic_ref<double>(e).fetch_add(luminance(weighted), std::memory_order_relaxed);
  else e += luminance(weighted);
}

void TechniqueFilms::finishPass(double splatScale) {
  if (moments_.empty()) return;
  for (const Technique x : techniquesUpTo(maxLength_, families_)) {
    std::vector<double>& e = passEstimate_[x.index()];
    std::vector<double>& m = moments_[x.index()];
    const double scale = x.t == 1 && !x.isMerge() ? splatScale : 1.0;
    for (size_t i = 0; i < e.size(); ++i) {
      const double v = e[i] * scale;
      m[i] += v * v;
      e[i] = 0.0;
    }
  }
}

void TechniqueFilms::discardPass() {
  for (std::vector<double>& e : passEstimate_) std::fill(e.begin(), e.end(), 0.0);
}

void TechniqueFilms::addSampleable(int k, uint64_t sampleableBy, Vec2 pRaster, bool splat, double weightedLuminance) {
  if (sampleable_.empty() || k < 1 || k > maxLength_ || !(weightedLuminance != 0.0)) return;
  const long long p = pixel(pRaster);
  if (p < 0) return;
  // A camera contribution lands on the sample's own pixel, which the calling thread owns for the
  // pass; splats land anywhere and go to buffers of their own, atomically.
  for (const Technique x : techniquesOfLength(k, families_)) {
    if (x.slot() >= 64 || !(sampleableBy >> x.slot() & 1)) continue;
    double& v = sampleable_[buffer(x, splat)][static_cast<size_t>(p)];
    if (splat)
      std::atomic_ref<double>(v).fetch_add(weightedLuminance, std::memory_order_relaxed);
    else
      v += weightedLuminance;
  }
}

void TechniqueFilms::clear() {
  for (std::vector<double>& b : buffers_) std::fill(b.begin(), b.end(), 0.0);
  for (std::vector<double>& b : sampleable_) std::fill(b.begin(), b.end(), 0.0);
  for (std::vector<double>& b : moments_) std::fill(b.begin(), b.end(), 0.0);
  discardPass();
}

std::vector<std::span<double>> TechniqueFilms::sums() {
  std::vector<std::span<double>> all;
  for (std::vector<double>& b : buffers_) all.emplace_back(b);
  for (std::vector<double>& b : sampleable_) all.emplace_back(b);
  for (std::vector<double>& b : moments_) all.emplace_back(b);  // (the pass estimates are zero between passes)
  return all;
}

namespace {

// Film::readout's normalisation: camera samples by samples per pixel, splats by the number of
// light subpaths over the pixel count.
double normalisation(bool splat, int width, int height, uint64_t samplesPerPixel, uint64_t lightSubpaths) {
  const double pixels = static_cast<double>(width) * static_cast<double>(height);
  return splat ? (lightSubpaths ? pixels / static_cast<double>(lightSubpaths) : 0.0)
               : (samplesPerPixel ? 1.0 / static_cast<double>(samplesPerPixel) : 0.0);
}

}  // namespace

Image TechniqueFilms::readout(Technique x, bool unweighted, uint64_t samplesPerPixel, uint64_t lightSubpaths) const {
  Image img{width_, height_, std::vector<float>(3 * static_cast<size_t>(width_) * static_cast<size_t>(height_), 0.f)};
  if (!covers(x)) return img;
  const double scale = normalisation(x.t == 1 && !x.isMerge(), width_, height_, samplesPerPixel, lightSubpaths);
  const std::vector<double>& b = buffers_[buffer(x, unweighted)];
  for (size_t i = 0; i < b.size(); ++i) img.rgb[i] = static_cast<float>(b[i] * scale);
  return img;
}

std::vector<float> TechniqueFilms::readoutSampleable(Technique x, uint64_t samplesPerPixel,
                                                     uint64_t lightSubpaths) const {
  std::vector<float> out(static_cast<size_t>(width_) * static_cast<size_t>(height_), 0.f);
  if (sampleable_.empty() || !covers(x)) return out;
  const double camera = normalisation(false, width_, height_, samplesPerPixel, lightSubpaths);
  const double splat = normalisation(true, width_, height_, samplesPerPixel, lightSubpaths);
  const std::vector<double>& c = sampleable_[buffer(x, false)];
  const std::vector<double>& l = sampleable_[buffer(x, true)];
  for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(c[i] * camera + l[i] * splat);
  return out;
}

std::vector<float> TechniqueFilms::readoutVariance(Technique x, uint64_t passes, uint64_t samplesPerPixel,
                                                   uint64_t lightSubpaths) const {
  std::vector<float> out(static_cast<size_t>(width_) * static_cast<size_t>(height_), 0.f);
  if (moments_.empty() || !covers(x) || passes < 2) return out;
  // The mean in double, as readout normalises it (a float mean would cancel the digits of a
  // variance far below its square).
  const double scale = normalisation(x.t == 1 && !x.isMerge(), width_, height_, samplesPerPixel, lightSubpaths);
  const std::vector<double>& w = buffers_[buffer(x, false)];
  const std::vector<double>& m = moments_[x.index()];
  const auto n = static_cast<double>(passes);
  for (size_t i = 0; i < out.size(); ++i) {
    // luminance()'s weights, in double: the mean of the passes' luminances.
    const double mu = scale * (0.2126 * w[3 * i] + 0.7152 * w[3 * i + 1] + 0.0722 * w[3 * i + 2]);
    out[i] = static_cast<float>(std::max(0.0, (m[i] - n * mu * mu) / (n - 1.0)));
  }
  return out;
}

}  // namespace pathlab
