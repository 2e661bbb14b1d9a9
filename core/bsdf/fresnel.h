// Fresnel reflectance (Schlick's approximation and the exact dielectric one) and refraction.
#pragma once

#include "core/math/types.h"

#include <optional>

namespace pathlab {

// Schlick 1994 with an explicit F90 (KHR_materials_specular): F0 + (F90 - F0) (1 - cos)^5.
inline Spectrum fresnelSchlick(const Spectrum& f0, float f90, float cosTheta) {
  const float m = glm::clamp(1.f - cosTheta, 0.f, 1.f);
  const float m2 = m * m;
  return f0 + (Spectrum(f90) - f0) * (m2 * m2 * m);
}
inline float fresnelSchlick(float f0, float f90, float cosTheta) {
  const float m = glm::clamp(1.f - cosTheta, 0.f, 1.f);
  const float m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

// Unpolarised Fresnel reflectance of a dielectric interface for cosThetaI >= 0 on the incident
// side and eta = eta_transmitted / eta_incident; 1 under total internal reflection.
inline float fresnelDielectric(float cosThetaI, float eta) {
  cosThetaI = glm::clamp(cosThetaI, 0.f, 1.f);
  const float sin2T = (1.f - cosThetaI * cosThetaI) / (eta * eta);
  if (sin2T >= 1.f) return 1.f;
  const float cosT = safeSqrt(1.f - sin2T);
  const float parl = (eta * cosThetaI - cosT) / (eta * cosThetaI + cosT);
  const float perp = (cosThetaI - eta * cosT) / (cosThetaI + eta * cosT);
  const float f = 0.5f * (parl * parl + perp * perp);
  return std::isfinite(f) ? glm::clamp(f, 0.f, 1.f) : 1.f;
}

// 1 - fresnelDielectric for a refraction pair whose cosines (both >= 0) are known, written as
// 1 - r^2 = 4 eta cosI cosT / (...)^2 per polarisation: free of the cancellation of 1 - F near
// total internal reflection, and the same from either side (swap the cosines, invert eta).
inline float fresnelDielectricTransmittance(float cosThetaI, float cosThetaT, float eta) {
  const float a = cosThetaI + eta * cosThetaT, b = eta * cosThetaI + cosThetaT;
  if (a <= 0.f || b <= 0.f) return 0.f;
  const float t = 2.f * eta * cosThetaI * cosThetaT * (1.f / (a * a) + 1.f / (b * b));
  return std::isfinite(t) ? glm::clamp(t, 0.f, 1.f) : 0.f;
}

// Refracts w (pointing away, w.n > 0) through the interface with normal n and relative index
// eta = eta_transmitted / eta_incident; nullopt under total internal reflection.
inline std::optional<Vec3> refract(const Vec3& w, const Vec3& n, float eta) {
  const float cosI = glm::dot(w, n);
  const float sin2T = (1.f - cosI * cosI) / (eta * eta);
  if (sin2T >= 1.f) return std::nullopt;
  const float cosT = safeSqrt(1.f - sin2T);
  return -w / eta + (cosI / eta - cosT) * n;
}

inline Vec3 reflect(const Vec3& w, const Vec3& n) { return 2.f * glm::dot(w, n) * n - w; }

}  // namespace pathlab
