// LightBounds: the importance bound and the union of two bounds (pbrt-v4 lights.cpp,
// DirectionCone Union; Conty Estevez and Kulla 2018, sec. 4).
#include "core/lights/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab {

namespace {

// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b.
float cosSubClamped(float sinA, float cosA, float sinB, float cosB) {
  return cosA > cosB ? 1.f : cosA * cosB + sinA * sinB;
}
float sinSubClamped(float sinA, float cosA, float sinB, float cosB) {
  return cosA > cosB ? 0.f : sinA * cosB - cosA * sinB;
}

float safeAcos(float x) { return std::acos(std::clamp(x, -1.f, 1.f)); }

// `v` turned by `angle` about the unit axis `k` (Rodrigues).
Vec3 rotate(const Vec3& v, const Vec3& k, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  return v * c + glm::cross(k, v) * s + k * (glm::dot(k, v) * (1.f - c));
}

}  // namespace

float LightBounds::importance(const LightSampleContext& ctx) const {
  // The box's bounding sphere: the angle theta_b it subtends at p (everything when p is inside).
  const Vec3 pc = centroid();
  const float radius2 = 0.25f * glm::dot(hi - lo, hi - lo);
  const Vec3 toP = ctx.p - pc;
  const float dist2 = glm::dot(toP, toP);
  // The direction from the emitters toward p (any, when p is their centre).
  const Vec3 wi = dist2 > 0.f ? toP / std::sqrt(dist2) : Vec3(0.f, 0.f, 1.f);
  float d2 = dist2;
  float cosThetaB = -1.f, sinThetaB = 0.f;
  if (d2 > radius2) {
    const float sin2 = radius2 / d2;
    cosThetaB = safeSqrt(1.f - sin2);
    sinThetaB = std::sqrt(sin2);
  }
  // Near or inside the box the distance is that of its surface at most: clamp, as pbrt-v4 does
  // (with the radius squared, so the units agree), and never below a tiny floor (a point light).
  d2 = std::max({d2, radius2, 1e-20f});

  // theta' = max(0, theta_w - theta_o - theta_b): the smallest angle between an emitter's normal
  // and the direction toward p that the bounds allow.
  float cosThetaW = glm::dot(w, wi);
  if (twoSided) cosThetaW = std::abs(cosThetaW);
  const float sinThetaW = safeSqrt(1.f - cosThetaW * cosThetaW);
  const float sinThetaO = safeSqrt(1.f - cosThetaO * cosThetaO);
  const float cosThetaX = cosSubClamped(sinThetaW, cosThetaW, sinThetaO, cosThetaO);
  const float sinThetaX = sinSubClamped(sinThetaW, cosThetaW, sinThetaO, cosThetaO);
  const float cosThetaP = cosSubClamped(sinThetaX, cosThetaX, sinThetaB, cosThetaB);
  if (cosThetaP <= cosThetaE) return 0.f;

  float importance = phi * cosThetaP / d2;
  if (ctx.n != Vec3(0.f)) {
    // The receiver's cosine, with the same slack: |cos| (light may arrive from either side of a
    // transmitting surface).
    const float cosThetaI = absDot(wi, ctx.n);
    const float sinThetaI = safeSqrt(1.f - cosThetaI * cosThetaI);
    importance *= cosSubClamped(sinThetaI, cosThetaI, sinThetaB, cosThetaB);
  }
  if (!(importance > 0.f)) return 0.f;
  return std::min(importance, std::numeric_limits<float>::max());
}

LightBounds unionOf(const LightBounds& a, const LightBounds& b) {
  if (!(a.phi > 0.f)) return b;
  if (!(b.phi > 0.f)) return a;
  LightBounds u;
  u.lo = glm::min(a.lo, b.lo);
  u.hi = glm::max(a.hi, b.hi);
  u.phi = a.phi + b.phi;
  u.cosThetaE = std::min(a.cosThetaE, b.cosThetaE);
  u.twoSided = a.twoSided || b.twoSided;
  // The normal cones: one holds the other, or the cone spanning both (pbrt-v4 DirectionCone Union).
  const float thetaA = safeAcos(a.cosThetaO), thetaB = safeAcos(b.cosThetaO);
  const float thetaD = safeAcos(glm::dot(a.w, b.w));
  if (std::min(thetaD + thetaB, kPi) <= thetaA) {
    u.w = a.w, u.cosThetaO = a.cosThetaO;
    return u;
  }
  if (std::min(thetaD + thetaA, kPi) <= thetaB) {
    u.w = b.w, u.cosThetaO = b.cosThetaO;
    return u;
  }
  const float thetaO = 0.5f * (thetaA + thetaD + thetaB);
  const Vec3 axis = glm::cross(a.w, b.w);
  const float axisLength = glm::length(axis);
  if (thetaO >= kPi || !(axisLength > 0.f)) {
    u.w = a.w, u.cosThetaO = -1.f;  // every direction
    return u;
  }
  u.w = glm::normalize(rotate(a.w, axis / axisLength, thetaO - thetaA));
  u.cosThetaO = std::cos(thetaO);
  return u;
}

float orientationMeasure(const LightBounds& b) {
  const float thetaO = safeAcos(b.cosThetaO), thetaE = safeAcos(b.cosThetaE);
  const float thetaW = std::min(thetaO + thetaE, kPi);
  const float sinThetaO = safeSqrt(1.f - b.cosThetaO * b.cosThetaO);
  return 2.f * kPi * (1.f - b.cosThetaO) +
         kPi / 2.f * (2.f * thetaW * sinThetaO - std::cos(thetaO - 2.f * thetaW) - 2.f * thetaO * sinThetaO + b.cosThetaO);
}

}  // namespace pathlab
