// Homogeneous media: glTF's parameters, transmittance and distance sampling.
#include "core/media/medium.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

namespace {
// Extinction of a channel whose attenuation colour is 0 ("nothing passes"): finite, so that
// exp(-sigma t) is 0 beyond a few thousandths of a unit without infinities in the arithmetic.
constexpr float kOpaqueSigma = 1e4f;

float multiscatterAlbedo(float s) { return (1.f - s) * (1.f - 0.139f * s) / (1.f + 1.17f * s); }
}  // namespace

Spectrum singleScatterAlbedo(const Spectrum& multiscatter, float g) {
  Spectrum albedo(0.f);
  for (int c = 0; c < 3; ++c) {
    const float target = std::clamp(multiscatter[c], 0.f, 1.f);
    float lo = 0.f, hi = 1.f;  // s, with multiscatterAlbedo(lo) >= target >= multiscatterAlbedo(hi)
    for (int i = 0; i < 40; ++i) {
      const float mid = 0.5f * (lo + hi);
      (multiscatterAlbedo(mid) > target ? lo : hi) = mid;
    }
    const float s2 = sqr(0.5f * (lo + hi));
    albedo[c] = std::clamp((1.f - s2) / (1.f - g * s2), 0.f, 1.f);
  }
  return albedo;
}

HomogeneousMedium HomogeneousMedium::fromVolume(const VolumeDesc& v) {
  HomogeneousMedium m;
  for (int c = 0; c < 3; ++c) {
    const float colour = std::clamp(v.attenuationColor[c], 0.f, 1.f);
    if (!(v.attenuationDistance < std::numeric_limits<float>::infinity()) || colour >= 1.f) continue;
    m.sigmaT[c] = colour > 0.f ? std::min(-std::log(colour) / v.attenuationDistance, kOpaqueSigma) : kOpaqueSigma;
  }
  m.g = std::clamp(v.anisotropy, -0.99f, 0.99f);
  if (v.scatters) m.sigmaS = singleScatterAlbedo(v.multiscatterColor, m.g) * m.sigmaT;
  return m;
}

Spectrum HomogeneousMedium::transmittance(float distance) const {
  if (isVacuum()) return Spectrum(1.f);
  if (!(distance < std::numeric_limits<float>::infinity())) {
    Spectrum T(1.f);
    for (int c = 0; c < 3; ++c) T[c] = sigmaT[c] > 0.f ? 0.f : 1.f;
    return T;
  }
  return glm::exp(-sigmaT * distance);
}

float distancePdf(const HomogeneousMedium& m, float t) {
  const Spectrum T = m.transmittance(t);
  return (m.sigmaT.r * T.r + m.sigmaT.g * T.g + m.sigmaT.b * T.b) / 3.f;
}

float passProbability(const HomogeneousMedium& m, float tMax) {
  const Spectrum T = m.transmittance(tMax);
  return (T.r + T.g + T.b) / 3.f;
}

DistanceSample sampleDistance(const HomogeneousMedium& m, float tMax, float uChannel, float u) {
  DistanceSample d;
  const int c = std::min(static_cast<int>(uChannel * 3.f), 2);
  const float sigma = m.sigmaT[c];
  // -log(1 - u) / sigma: u < 1, so finite; a channel without extinction never scatters.
  const float t = sigma > 0.f ? -std::log1p(-u) / sigma : std::numeric_limits<float>::infinity();
  if (t < tMax) {
    d.scattered = true;
    d.t = t;
    const float pdf = distancePdf(m, t);
    d.weight = pdf > 0.f ? m.sigmaS * m.transmittance(t) / pdf : Spectrum(0.f);
    return d;
  }
  const float pass = passProbability(m, tMax);
  d.weight = pass > 0.f ? m.transmittance(tMax) / pass : Spectrum(0.f);
  return d;
}

}  // namespace pathlab
