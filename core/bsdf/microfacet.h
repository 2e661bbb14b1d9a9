// Isotropic GGX (Trowbridge-Reitz) microfacet distribution in a local frame with the normal as +z:
// D, Smith's masking (height-correlated G2), and visible-normal sampling.
#pragma once

#include "core/math/types.h"

namespace pathlab::ggx {

// Walter et al. 2007, eq. 33, written with sin^2 = x^2 + y^2 so that tiny alphas near the peak
// do not lose precision to 1 - cos^2.
inline float D(const Vec3& h, float alpha) {
  if (h.z <= 0.f) return 0.f;
  const float a2 = alpha * alpha;
  const float denom = a2 * h.z * h.z + h.x * h.x + h.y * h.y;
  if (denom <= 0.f) return 0.f;
  return a2 / (kPi * denom * denom);
}

// Smith Lambda for GGX (Heitz 2014, eq. 72), in the cancellation-free form
// (sqrt(1 + x) - 1) / 2 = x / (2 (sqrt(1 + x) + 1)) with x = alpha^2 tan^2(theta).
inline float Lambda(const Vec3& w, float alpha) {
  const float cos2 = w.z * w.z;
  if (cos2 <= 0.f) return 0.f;  // callers never use a grazing w (they return zero first)
  const float x = alpha * alpha * (w.x * w.x + w.y * w.y) / cos2;
  return x / (2.f * (std::sqrt(1.f + x) + 1.f));
}

inline float G1(const Vec3& w, float alpha) { return 1.f / (1.f + Lambda(w, alpha)); }

// Height-correlated Smith masking-shadowing (Heitz 2014, eq. 99), used for reflection and
// refraction alike (as pbrt-v4 does): symmetric in (wo, wi), hence reciprocal.
inline float G2(const Vec3& wo, const Vec3& wi, float alpha) {
  return 1.f / (1.f + Lambda(wo, alpha) + Lambda(wi, alpha));
}

// Density of the visible normals seen from wo (wo.z > 0): D_wo(h) = G1(wo) max(0, wo.h) D(h) / wo.z
// (Heitz 2018, eq. 3).
inline float visibleNormalPdf(const Vec3& wo, const Vec3& h, float alpha) {
  const float cosO = glm::dot(wo, h);
  if (wo.z <= 0.f || cosO <= 0.f) return 0.f;
  return G1(wo, alpha) * cosO * D(h, alpha) / wo.z;
}

// Heitz 2018, "Sampling the GGX Distribution of Visible Normals", listing 1 (isotropic). wo.z > 0.
inline Vec3 sampleVisibleNormal(const Vec3& wo, float alpha, Vec2 u) {
  const Vec3 vh = glm::normalize(Vec3(alpha * wo.x, alpha * wo.y, wo.z));
  const float lensq = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = lensq > 0.f ? Vec3(-vh.y, vh.x, 0.f) / std::sqrt(lensq) : Vec3(1.f, 0.f, 0.f);
  const Vec3 t2 = glm::cross(vh, t1);
  const float r = std::sqrt(u.x);
  const float phi = 2.f * kPi * u.y;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.f + vh.z);
  const float p2 = (1.f - s) * safeSqrt(1.f - p1 * p1) + s * r * std::sin(phi);
  const Vec3 nh = p1 * t1 + p2 * t2 + safeSqrt(1.f - p1 * p1 - p2 * p2) * vh;
  return glm::normalize(Vec3(alpha * nh.x, alpha * nh.y, glm::max(nh.z, 1e-7f)));
}

}  // namespace pathlab::ggx
