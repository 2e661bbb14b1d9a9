// Warps from the unit square to sampling domains, each with its density ("pdf twin") and, where
// the tests need it, its inverse. Densities are in the domain's natural measure (solid angle
// for directions, area for points).
#pragma once

#include "core/math/types.h"

namespace pathlab {

// Shirley-Chiu concentric map to the unit disk.
inline Vec2 sampleUniformDiskConcentric(Vec2 u) {
  const Vec2 o = 2.f * u - Vec2(1.f);
  if (o.x == 0.f && o.y == 0.f) return {0.f, 0.f};
  float r, theta;
  if (std::abs(o.x) > std::abs(o.y)) {
    r = o.x;
    theta = (kPi / 4.f) * (o.y / o.x);
  } else {
    r = o.y;
    theta = kPi / 2.f - (kPi / 4.f) * (o.x / o.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

// Malley's method: cosine-weighted hemisphere around +z.
inline Vec3 sampleCosineHemisphere(Vec2 u) {
  const Vec2 d = sampleUniformDiskConcentric(u);
  const float z = safeSqrt(1.f - d.x * d.x - d.y * d.y);
  return {d.x, d.y, z};
}
inline float cosineHemispherePdf(float cosTheta) { return glm::max(cosTheta, 0.f) * kInvPi; }

inline Vec3 sampleUniformSphere(Vec2 u) {
  const float z = 1.f - 2.f * u.x;
  const float r = safeSqrt(1.f - z * z);
  const float phi = 2.f * kPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float uniformSpherePdf() { return kInv4Pi; }

// Uniform in the cone of directions within acos(cosThetaMax) of +z.
inline Vec3 sampleUniformCone(Vec2 u, float cosThetaMax) {
  const float cosTheta = (1.f - u.x) + u.x * cosThetaMax;
  const float sinTheta = safeSqrt(1.f - cosTheta * cosTheta);
  const float phi = 2.f * kPi * u.y;
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}
inline float uniformConePdf(float cosThetaMax) { return 1.f / (2.f * kPi * (1.f - cosThetaMax)); }

// Uniform barycentrics (b0, b1) on a triangle; b2 = 1 - b0 - b1. Heitz 2019 low-distortion map.
inline Vec2 sampleUniformTriangle(Vec2 u) {
  float b0, b1;
  if (u.x < u.y) {
    b0 = u.x / 2.f;
    b1 = u.y - b0;
  } else {
    b1 = u.y / 2.f;
    b0 = u.x - b1;
  }
  return {b0, b1};
}

}  // namespace pathlab
