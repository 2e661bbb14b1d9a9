// VarianceAwareFactors: the regions, the per-pass sums and the factors (variance_aware_mis.h).
#include "core/bpt/variance_aware_mis.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace pathlab {

namespace {
// Per region and technique: five doubles (the pass's two sums, the three over passes) and the factor.
constexpr uint64_t kBytesPerSlot = 5 * sizeof(double) + sizeof(float);
}  // namespace

uint64_t VarianceAwareFactors::bytesFor(int width, int height, uint64_t regions, int maxLength) {
  return regions * Technique::countUpTo(maxLength) * kBytesPerSlot +
         static_cast<uint64_t>(width) * static_cast<uint64_t>(height) * sizeof(int32_t);
}

VarianceAwareFactors::VarianceAwareFactors(int width, int height, std::vector<int32_t> regionOfPixel, int regions,
                                           int maxLength)
    : width_(width),
      height_(height),
      maxLength_(maxLength),
      techniques_(Technique::countUpTo(maxLength)),
      regions_(regions),
      regionOfPixel_(std::move(regionOfPixel)) {
  regionPixels_.assign(static_cast<size_t>(regions_), 0.0);
  for (const int32_t r : regionOfPixel_)
    if (r >= 0) regionPixels_[static_cast<size_t>(r)] += 1.0;
  const size_t slots = static_cast<size_t>(regions_) * techniques_;
  for (std::vector<double>* v : {&passX_, &passX2_, &sumA1_, &sumA1Squared_, &sumA2_}) v->assign(slots, 0.0);
  factors_.assign(slots, 1.f);
}

int VarianceAwareFactors::regionOf(Vec2 pRaster) const {
  if (!(pRaster.x >= 0.f && pRaster.y >= 0.f)) return -1;
  const int x = static_cast<int>(pRaster.x), y = static_cast<int>(pRaster.y);
  if (x >= width_ || y >= height_) return -1;
  return regionOfPixel_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
}

float VarianceAwareFactors::factor(int region, Technique x) const {
  if (!active_ || region < 0 || region >= regions_ || !x.valid() || x.length() > maxLength_) return 1.f;
  return factors_[slot(region, x)];
}

void VarianceAwareFactors::add(Technique x, Vec2 pRaster, float luminance, std::vector<Splat>& splats) {
  const int region = regionOf(pRaster);
  if (region < 0 || !x.valid() || x.length() > maxLength_ || !(luminance > 0.f)) return;
  const size_t i = slot(region, x);
  if (!x.isMerge() && x.t == 1) {
    splats.push_back(Splat{static_cast<uint32_t>(i), luminance});
    return;
  }
  const double v = luminance;
  passX_[i] += v;
  passX2_[i] += v * v;
}

void VarianceAwareFactors::addSplats(std::vector<Splat>& splats) {
  for (const Splat& s : splats) {
    const double v = s.luminance;
    passX_[s.slot] += v;
    passX2_[s.slot] += v * v;
  }
  splats.clear();
}

float VarianceAwareFactors::factorFromSums(double sumA1, double sumA1Squared, double sumA2, uint64_t passes) {
  if (passes < 2 || !(sumA2 > 0.0)) return 1.f;  // never contributed here: nothing to correct
  const double n = static_cast<double>(passes);
  const double variance = (sumA1Squared - sumA1 * sumA1 / n) / (n - 1.0);
  const double moment = sumA2 / n;
  const double c = variance > 0.0 ? moment / variance : static_cast<double>(kVarianceAwareMaxFactor);
  if (!std::isfinite(c)) return 1.f;
  return static_cast<float>(std::clamp(c, 1.0 / kVarianceAwareMaxFactor, static_cast<double>(kVarianceAwareMaxFactor)));
}

void VarianceAwareFactors::finishPass(double samplesPerPixel) {
  ++passes_;
  active_ = passes_ >= static_cast<uint64_t>(kVarianceAwarePilotPasses);
  const uint64_t passes = passes_;
  tbb::parallel_for(0, regions_, [&](int region) {
    // N: the region's samples this pass (its light subpaths' splats are as many and normalised alike).
    const double n = regionPixels_[static_cast<size_t>(region)] * samplesPerPixel;
    const double invN = n > 0.0 ? 1.0 / n : 0.0;
    const size_t begin = static_cast<size_t>(region) * techniques_;
    for (size_t i = begin; i < begin + techniques_; ++i) {
      const double a1 = passX_[i] * invN;
      sumA1_[i] += a1;
      sumA1Squared_[i] += a1 * a1;
      sumA2_[i] += passX2_[i] * invN * invN;
      passX_[i] = 0.0;
      passX2_[i] = 0.0;
      if (active_) factors_[i] = factorFromSums(sumA1_[i], sumA1Squared_[i], sumA2_[i], passes);
    }
  });
}

void VarianceAwareFactors::discardPass() {
  std::fill(passX_.begin(), passX_.end(), 0.0);
  std::fill(passX2_.begin(), passX2_.end(), 0.0);
}

}  // namespace pathlab
