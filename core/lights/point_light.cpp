// Point and spot lights: sampling and evaluation (point_light.h).
#include "core/lights/point_light.h"

#include "core/sampling/warp.h"

#include <algorithm>

namespace pathlab {

namespace {

// KHR_lights_punctual, "Inner and Outer Cone Angles": the spec's smooth falloff, squared.
float spotFalloff(float cosTheta, float cosInner, float cosOuter) {
  const float scale = 1.f / std::max(0.001f, cosInner - cosOuter);
  const float offset = -cosOuter * scale;
  const float a = glm::clamp(cosTheta * scale + offset, 0.f, 1.f);
  return a * a;
}

// Exact solid-angle integral of spotFalloff: with c = cos theta, the falloff is
// (s (c - cosOuter))^2 on [cosOuter, c1] and 1 on [c1, 1], c1 = min(1, cosOuter + 1/s), so
// integral = 2 pi [ (1 - c1) + s^2 (c1 - cosOuter)^3 / 3 ].
double spotFalloffIntegral(float cosInner, float cosOuter) {
  const double s = 1.0 / std::max(0.001, static_cast<double>(cosInner) - cosOuter);
  const double c1 = std::min(1.0, cosOuter + 1.0 / s);
  const double ramp = c1 - cosOuter;
  return 2.0 * static_cast<double>(kPi) * ((1.0 - c1) + s * s * ramp * ramp * ramp / 3.0);
}

// A cone whose pdf stays finite in float: a spot narrower than this is a numerical point.
constexpr float kMinConeAngle = 1e-3f;

// The light at `position` seen from ref: intensity / d^2 toward ref, a delta (pdf one).
template <class Punctual>
LightLiSample punctualLi(const Punctual& light, const Vec3& ref) {
  LightLiSample s;
  const Vec3 toLight = light.position() - ref;
  const float dist2 = glm::dot(toLight, toLight);
  s.pLight = light.position();
  s.isDelta = true;
  if (!(dist2 > 0.f)) return s;
  s.dist = std::sqrt(dist2);
  s.wi = toLight / s.dist;
  s.pdfW = 1.f;
  s.Li = light.intensity(-s.wi) / dist2;
  return s;
}

// A box of zero size at the light, phi = pi I; every direction unless the caller narrows it.
LightBounds punctualBounds(const Vec3& position, const Spectrum& I) {
  LightBounds b;
  b.lo = b.hi = position;
  b.phi = luminance(I) * kPi;
  return b;
}

}  // namespace

LightLiSample PointLight::sampleLi(const Vec3& ref, Vec2) const { return punctualLi(*this, ref); }

LightLeSample PointLight::sampleLe(Vec2, Vec2 uDir) const {
  LightLeSample s;
  const Vec3 dir = sampleUniformSphere(uDir);
  s.ray = Ray{position_, dir};
  s.pdfPosA = 1.f;
  s.pdfDirW = uniformSpherePdf();
  s.Le = I_;
  return s;
}

EmissionPdf PointLight::pdfLe(const Vec3&) const { return EmissionPdf{1.f, uniformSpherePdf()}; }

Spectrum PointLight::intensity(const Vec3&) const { return I_; }

Spectrum PointLight::power() const { return I_ * (4.f * kPi); }

LightBounds PointLight::lightBounds() const {
  LightBounds b = punctualBounds(position_, I_);
  b.cosThetaO = -1.f;  // every direction
  b.cosThetaE = 0.f;
  return b;
}

SpotLight::SpotLight(const Vec3& position, const Vec3& direction, const Spectrum& intensity, float innerConeAngle,
                     float outerConeAngle)
    : position_(position), I_(intensity), n_(glm::normalize(direction)), frame_(n_) {
  const float outer = glm::clamp(outerConeAngle, kMinConeAngle, kPi);
  const float inner = glm::clamp(innerConeAngle, 0.f, outer);
  cosOuter_ = std::cos(outer);
  cosInner_ = std::cos(inner);
}

LightLiSample SpotLight::sampleLi(const Vec3& ref, Vec2) const { return punctualLi(*this, ref); }

LightLeSample SpotLight::sampleLe(Vec2, Vec2 uDir) const {
  LightLeSample s;
  const Vec3 dir = frame_.toWorld(sampleUniformCone(uDir, cosOuter_));
  s.ray = Ray{position_, dir};
  s.pdfPosA = 1.f;
  s.pdfDirW = uniformConePdf(cosOuter_);
  s.Le = intensity(dir);
  return s;
}

EmissionPdf SpotLight::pdfLe(const Vec3& dir) const {
  return EmissionPdf{1.f, glm::dot(n_, dir) >= cosOuter_ ? uniformConePdf(cosOuter_) : 0.f};
}

Spectrum SpotLight::intensity(const Vec3& w) const {
  return I_ * spotFalloff(glm::dot(n_, w), cosInner_, cosOuter_);
}

Spectrum SpotLight::power() const { return I_ * static_cast<float>(spotFalloffIntegral(cosInner_, cosOuter_)); }

LightBounds SpotLight::lightBounds() const {
  // Full intensity inside the inner cone, falling to zero at the outer one (pbrt-v4 SpotLight).
  LightBounds b = punctualBounds(position_, I_);
  b.w = n_;
  // theta_e widened by 1e-3: with equal cones (a hard edge) cos(0) = 1 would refuse every
  // receiver, even inside the cone (importance needs cos(theta') > cos(theta_e)), and the
  // margin keeps the float comparison conservative just inside the outer cone.
  b.cosThetaO = cosInner_;
  b.cosThetaE = std::cos(std::max(0.f, std::acos(std::clamp(cosOuter_, -1.f, 1.f)) -
                                           std::acos(std::clamp(cosInner_, -1.f, 1.f))) +
                         1e-3f);
  return b;
}

}  // namespace pathlab
