// Area lights: sampling and evaluation of one emissive triangle (area_light.h).
#include "core/lights/area_light.h"

#include "core/sampling/warp.h"
#include "core/texture/texture_integral.h"

#include <algorithm>

namespace pathlab {

AreaLight::AreaLight(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& uv0, const Vec2& uv1,
                     const Vec2& uv2, const Spectrum& emission, const Texture* emissiveTexture, bool twoSided)
    : emission_(emission), p_{p0, p1, p2}, uv_{uv0, uv1, uv2}, twoSided_(twoSided), texture_(emissiveTexture) {
  const Vec3 c = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(c);
  area_ = 0.5f * len;
  // A degenerate triangle keeps area 0: power() is 0, so the LightSet never chooses it.
  n_ = len > 0.f ? c / len : Vec3(0.f, 0.f, 1.f);
  frame_ = Frame(n_);
  // The texels the triangle covers, not the whole texture's average: a triangle over a black part
  // of the texture has no power and is never chosen (Scene leaves it out of the lights).
  meanLe_ = emissiveTexture ? emission * Spectrum(meanOverTriangle(*emissiveTexture, uv0, uv1, uv2)) : emission;
}

AreaLight::TrianglePoint AreaLight::samplePoint(Vec2 u) const {
  const Vec2 b = sampleUniformTriangle(u);
  const float b2 = 1.f - b.x - b.y;
  TrianglePoint t;
  t.p = b.x * p_[0] + b.y * p_[1] + b2 * p_[2];
  t.uv = b.x * uv_[0] + b.y * uv_[1] + b2 * uv_[2];
  t.pError = interpolationError(b.x, p_[0], b.y, p_[1], b2, p_[2]);
  return t;
}

LightLiSample AreaLight::sampleLi(const Vec3& ref, Vec2 u) const {
  LightLiSample s;
  if (area_ <= 0.f) return s;
  const TrianglePoint t = samplePoint(u);
  s.pError = t.pError;
  const Vec3 toLight = t.p - ref;
  const float dist2 = glm::dot(toLight, toLight);
  if (!(dist2 > 0.f)) return s;
  const float dist = std::sqrt(dist2);
  const Vec3 wi = toLight / dist;
  const float cosLight = absDot(n_, wi);
  s.pLight = t.p;
  s.uv = t.uv;
  s.nLight = n_;
  s.wi = wi;
  s.dist = dist;
  if (!(cosLight > 0.f)) return s;  // edge-on: zero density in solid angle, zero Li
  // Area to solid angle: dA = dist^2 / |cos theta_light| dw (pbrt-v3 eq. 5.6).
  s.pdfW = dist2 / (cosLight * area_);
  if (!std::isfinite(s.pdfW)) {
    s.pdfW = 0.f;
    return s;
  }
  s.Li = radiance(t.uv, -wi);
  return s;
}

float AreaLight::pdfLi(const Vec3& ref, const Vec3& pLight) const {
  if (area_ <= 0.f) return 0.f;
  const Vec3 toLight = pLight - ref;
  const float dist2 = glm::dot(toLight, toLight);
  if (!(dist2 > 0.f)) return 0.f;
  const float cosLight = absDot(n_, toLight) / std::sqrt(dist2);
  if (!(cosLight > 0.f)) return 0.f;
  const float pdf = dist2 / (cosLight * area_);
  return std::isfinite(pdf) ? pdf : 0.f;
}

LightLeSample AreaLight::sampleLe(Vec2 uPos, Vec2 uDir) const {
  LightLeSample s;
  if (area_ <= 0.f) return s;
  const TrianglePoint t = samplePoint(uPos);
  float side = 1.f, sideProb = 1.f;
  if (twoSided_) {
    // Reuse uDir.x to pick the side with probability 1/2, then stretch it back to [0,1).
    if (uDir.x < 0.5f) {
      uDir.x = std::min(uDir.x * 2.f, kOneMinusEpsilon);
    } else {
      uDir.x = std::min((uDir.x - 0.5f) * 2.f, kOneMinusEpsilon);
      side = -1.f;
    }
    sideProb = 0.5f;
  }
  const Vec3 local = sampleCosineHemisphere(uDir);
  const Vec3 dir = side * frame_.toWorld(local);
  s.ray = Ray{t.p, dir};
  s.pError = t.pError;
  s.uv = t.uv;
  s.n = n_;
  s.pdfPosA = 1.f / area_;
  s.pdfDirW = sideProb * cosineHemispherePdf(local.z);
  if (s.pdfDirW > 0.f) s.Le = radiance(t.uv, dir);
  return s;
}

EmissionPdf AreaLight::pdfLe(const Vec3& dir) const {
  EmissionPdf e;
  if (area_ <= 0.f) return e;
  e.pdfPosA = 1.f / area_;
  const float c = glm::dot(n_, dir);
  e.pdfDirW = twoSided_ ? 0.5f * std::abs(c) * kInvPi : cosineHemispherePdf(c);
  return e;
}

Spectrum AreaLight::radiance(Vec2 uv, const Vec3& w) const {
  if (!twoSided_ && !(glm::dot(n_, w) > 0.f)) return Spectrum(0.f);
  Spectrum le = emission_;
  if (texture_) le *= Spectrum(texture_->sample(uv));
  return le;
}

Spectrum AreaLight::power() const {
  // Phi = pi A <Le>: a Lambertian emitter radiates pi L per unit area on each emitting side,
  // <Le> the mean of radiance() over the triangle, which sampleLe's positions are uniform on.
  return meanLe_ * (kPi * area_ * (twoSided_ ? 2.f : 1.f));
}

LightBounds AreaLight::lightBounds() const {
  LightBounds b;
  b.lo = glm::min(p_[0], glm::min(p_[1], p_[2]));
  b.hi = glm::max(p_[0], glm::max(p_[1], p_[2]));
  b.phi = luminance(meanLe_) * kPi * area_;  // one side: a point sees one side of it
  b.w = n_;
  b.cosThetaO = 1.f;
  b.cosThetaE = 0.f;  // Lambertian: up to pi / 2 from the normal
  b.twoSided = twoSided_;
  return b;
}

}  // namespace pathlab
