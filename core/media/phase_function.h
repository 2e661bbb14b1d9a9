// The Henyey-Greenstein phase function (Henyey & Greenstein 1941; pbrt-v4 sec. 11.3.1): the
// "BSDF" of a medium vertex. Normalised over the sphere (no cosine factor: vertices in media are
// integrated with the volume measure, the seed's path integral). Symmetric in its two directions,
// so the forward and reverse densities of a direction pair are equal.
//
// Convention: cosTheta is the cosine of the scattering angle, between the direction light
// travelled (-wo, toward the vertex along its own subpath) and the direction it continues in (wi);
// g > 0 scatters forward. With wo and wi both pointing away from the vertex (bsdf.h), that is
// cosTheta = -dot(wo, wi).
#pragma once

#include "core/math/frame.h"
#include "core/math/types.h"

namespace pathlab {

inline float henyeyGreenstein(float cosTheta, float g) {
  const float denom = 1.f + g * g - 2.f * g * cosTheta;
  return kInv4Pi * (1.f - g * g) / (denom * safeSqrt(denom));
}

// Value (= density) of scattering from -wo into wi at a vertex with anisotropy g.
inline float phaseHG(const Vec3& wo, const Vec3& wi, float g) { return henyeyGreenstein(-glm::dot(wo, wi), g); }

// A direction wi distributed as phaseHG(wo, ., g), by inverting the HG CDF in cosTheta (pbrt-v4
// SampleHenyeyGreenstein); uniform on the sphere for |g| < 1e-3. Its density is phaseHG itself.
inline Vec3 samplePhaseHG(const Vec3& wo, float g, Vec2 u) {
  float cosTheta;
  if (std::abs(g) < 1e-3f) {
    cosTheta = 1.f - 2.f * u.x;
  } else {
    const float sq = (1.f - g * g) / (1.f + g - 2.f * g * u.x);
    cosTheta = (1.f + g * g - sq * sq) / (2.f * g);
  }
  cosTheta = glm::clamp(cosTheta, -1.f, 1.f);
  const float sinTheta = safeSqrt(1.f - cosTheta * cosTheta);
  const float phi = 2.f * kPi * u.y;
  // About the direction of travel -wo: cosTheta is measured from it.
  const Frame frame(-wo);
  return glm::normalize(frame.toWorld(Vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta)));
}

}  // namespace pathlab
