// Emitters: sampling and evaluation of area, point, spot, directional and environment lights (light.h).
#include "core/lights/light.h"

#include "core/sampling/warp.h"
#include "core/texture/texture_integral.h"

#include <algorithm>
#include <limits>

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

}  // namespace

Light Light::area(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& uv0, const Vec2& uv1,
                  const Vec2& uv2, const Spectrum& emission, const Texture* emissiveTexture,
                  bool twoSided) {
  Light l;
  l.type_ = LightType::Area;
  l.emission_ = emission;
  l.p_[0] = p0;
  l.p_[1] = p1;
  l.p_[2] = p2;
  l.uv_[0] = uv0;
  l.uv_[1] = uv1;
  l.uv_[2] = uv2;
  const Vec3 c = glm::cross(p1 - p0, p2 - p0);
  const float len = glm::length(c);
  l.area_ = 0.5f * len;
  // A degenerate triangle keeps area 0: power() is 0, so the LightSet never chooses it.
  l.n_ = len > 0.f ? c / len : Vec3(0.f, 0.f, 1.f);
  l.frame_ = Frame(l.n_);
  l.twoSided_ = twoSided;
  l.texture_ = emissiveTexture;
  // The texels the triangle covers, not the whole texture's average: a triangle over a black part
  // of the texture has no power and is never chosen (Scene leaves it out of the lights).
  l.meanLe_ = emissiveTexture ? emission * Spectrum(meanOverTriangle(*emissiveTexture, uv0, uv1, uv2))
                              : emission;
  return l;
}

Light Light::point(const Vec3& position, const Spectrum& intensity) {
  Light l;
  l.type_ = LightType::Point;
  l.emission_ = intensity;
  l.p_[0] = position;
  return l;
}

Light Light::spot(const Vec3& position, const Vec3& direction, const Spectrum& intensity,
                  float innerConeAngle, float outerConeAngle) {
  Light l;
  l.type_ = LightType::Spot;
  l.emission_ = intensity;
  l.p_[0] = position;
  l.n_ = glm::normalize(direction);
  l.frame_ = Frame(l.n_);
  const float outer = glm::clamp(outerConeAngle, kMinConeAngle, kPi);
  const float inner = glm::clamp(innerConeAngle, 0.f, outer);
  l.cosOuter_ = std::cos(outer);
  l.cosInner_ = std::cos(inner);
  return l;
}

Light Light::directional(const Vec3& direction, const Spectrum& irradiance,
                         const SceneBounds& bounds) {
  Light l;
  l.type_ = LightType::Directional;
  l.emission_ = irradiance;
  l.n_ = glm::normalize(direction);
  l.frame_ = Frame(l.n_);
  l.bounds_ = bounds;
  // An empty scene (radius 0) would make the disk pdf infinite.
  l.bounds_.radius = std::max(bounds.radius, 1e-3f);
  return l;
}

Light Light::environment(const EnvironmentLight* environment) {
  Light l;
  l.type_ = LightType::Environment;
  l.environment_ = environment;
  return l;
}

LightLiSample Light::sampleLi(const Vec3& ref, Vec2 u) const {
  LightLiSample s;
  switch (type_) {
    case LightType::Area: {
      if (area_ <= 0.f) return s;
      const Vec2 b = sampleUniformTriangle(u);
      const float b2 = 1.f - b.x - b.y;
      const Vec3 p = b.x * p_[0] + b.y * p_[1] + b2 * p_[2];
      const Vec2 uv = b.x * uv_[0] + b.y * uv_[1] + b2 * uv_[2];
      s.pError = interpolationError(b.x, p_[0], b.y, p_[1], b2, p_[2]);
      const Vec3 toLight = p - ref;
      const float dist2 = glm::dot(toLight, toLight);
      if (!(dist2 > 0.f)) return s;
      const float dist = std::sqrt(dist2);
      const Vec3 wi = toLight / dist;
      const float cosLight = absDot(n_, wi);
      s.pLight = p;
      s.uv = uv;
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
      s.Li = radiance(n_, uv, -wi);
      return s;
    }
    case LightType::Point:
    case LightType::Spot: {
      const Vec3 toLight = p_[0] - ref;
      const float dist2 = glm::dot(toLight, toLight);
      s.pLight = p_[0];
      s.isDelta = true;
      if (!(dist2 > 0.f)) return s;
      s.dist = std::sqrt(dist2);
      s.wi = toLight / s.dist;
      s.pdfW = 1.f;
      s.Li = intensity(-s.wi) / dist2;
      return s;
    }
    case LightType::Directional: {
      s.wi = -n_;
      s.Li = emission_;
      s.pdfW = 1.f;
      s.isDelta = true;
      s.pLight = ref - n_ * (2.f * bounds_.radius);
      s.dist = std::numeric_limits<float>::infinity();
      return s;
    }
    case LightType::Environment: {
      const EnvironmentDirection d = environment_->sampleDirection(u);
      if (!(d.pdfW > 0.f)) return s;
      s.wi = d.w;
      s.pdfW = d.pdfW;
      s.Li = environment_->Le(d.w);
      s.pLight = ref + d.w * (2.f * environment_->radius());
      s.dist = std::numeric_limits<float>::infinity();
      return s;
    }
  }
  return s;
}

float Light::pdfLi(const Vec3& ref, const Vec3& pLight, const Vec3& nLight) const {
  if (type_ != LightType::Area || area_ <= 0.f) return 0.f;
  // The triangle's own normal, as in sampleLi: the caller's may be an interpolated shading normal.
  (void)nLight;
  const Vec3 toLight = pLight - ref;
  const float dist2 = glm::dot(toLight, toLight);
  if (!(dist2 > 0.f)) return 0.f;
  const float cosLight = absDot(n_, toLight) / std::sqrt(dist2);
  if (!(cosLight > 0.f)) return 0.f;
  const float pdf = dist2 / (cosLight * area_);
  return std::isfinite(pdf) ? pdf : 0.f;
}

LightLeSample Light::sampleLe(Vec2 uPos, Vec2 uDir) const {
  LightLeSample s;
  switch (type_) {
    case LightType::Area: {
      if (area_ <= 0.f) return s;
      const Vec2 b = sampleUniformTriangle(uPos);
      const float b2 = 1.f - b.x - b.y;
      const Vec3 p = b.x * p_[0] + b.y * p_[1] + b2 * p_[2];
      const Vec2 uv = b.x * uv_[0] + b.y * uv_[1] + b2 * uv_[2];
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
      s.ray = Ray{p, dir};
      s.pError = interpolationError(b.x, p_[0], b.y, p_[1], b2, p_[2]);
      s.uv = uv;
      s.n = n_;
      s.pdfPosA = 1.f / area_;
      s.pdfDirW = sideProb * cosineHemispherePdf(local.z);
      if (s.pdfDirW > 0.f) s.Le = radiance(n_, uv, dir);
      return s;
    }
    case LightType::Point: {
      const Vec3 dir = sampleUniformSphere(uDir);
      s.ray = Ray{p_[0], dir};
      s.pdfPosA = 1.f;
      s.pdfDirW = uniformSpherePdf();
      s.Le = emission_;
      return s;
    }
    case LightType::Spot: {
      const Vec3 dir = frame_.toWorld(sampleUniformCone(uDir, cosOuter_));
      s.ray = Ray{p_[0], dir};
      s.pdfPosA = 1.f;
      s.pdfDirW = uniformConePdf(cosOuter_);
      s.Le = intensity(dir);
      return s;
    }
    case LightType::Directional: {
      // pbrt-v3 DistantLight::Sample_Le: a disk covering the scene's bounding sphere, set back
      // by one radius so every ray starts outside the scene.
      const Vec2 d = sampleUniformDiskConcentric(uPos);
      const float r = bounds_.radius;
      const Vec3 pDisk = bounds_.center + r * (d.x * frame_.s + d.y * frame_.t);
      s.ray = Ray{pDisk - n_ * r, n_};
      s.n = n_;
      s.pdfPosA = 1.f / (kPi * r * r);
      s.pdfDirW = 1.f;
      s.Le = emission_;
      return s;
    }
    case LightType::Environment: {
      // pbrt-v4 ImageInfiniteLight::SampleLe: the direction from the map, the origin on the disk.
      const EnvironmentDirection d = environment_->sampleDirection(uDir);
      if (!(d.pdfW > 0.f)) return s;
      s.ray = Ray{environment_->diskPoint(d.w, uPos), -d.w};
      s.n = -d.w;
      s.pdfPosA = environment_->pdfPosition();
      s.pdfDirW = d.pdfW;
      s.Le = environment_->Le(d.w);
      return s;
    }
  }
  return s;
}

EmissionPdf Light::pdfLe(const Vec3& p, const Vec3& n, const Vec3& dir) const {
  (void)p;
  (void)n;  // the triangle's own normal decides, as in sampleLe
  EmissionPdf e;
  switch (type_) {
    case LightType::Area: {
      if (area_ <= 0.f) return e;
      e.pdfPosA = 1.f / area_;
      const float c = glm::dot(n_, dir);
      e.pdfDirW = twoSided_ ? 0.5f * std::abs(c) * kInvPi : cosineHemispherePdf(c);
      return e;
    }
    case LightType::Point:
      e.pdfPosA = 1.f;
      e.pdfDirW = uniformSpherePdf();
      return e;
    case LightType::Spot:
      e.pdfPosA = 1.f;
      e.pdfDirW = glm::dot(n_, dir) >= cosOuter_ ? uniformConePdf(cosOuter_) : 0.f;
      return e;
    case LightType::Directional:
      // The disk covers the bounding sphere, so any point of the scene lies within it. The
      // direction is a delta; following pbrt's "remap zero to one", its density is 1.
      e.pdfPosA = 1.f / (kPi * sqr(bounds_.radius));
      e.pdfDirW = 1.f;
      return e;
    case LightType::Environment:
      e.pdfPosA = environment_->pdfPosition();
      e.pdfDirW = environment_->pdfDirection(-dir);
      return e;
  }
  return e;
}

Spectrum Light::radiance(const Vec3& n, Vec2 uv, const Vec3& w) const {
  (void)n;  // the triangle's winding decides the front, never a caller's shading normal
  if (type_ != LightType::Area) return Spectrum(0.f);
  if (!twoSided_ && !(glm::dot(n_, w) > 0.f)) return Spectrum(0.f);
  Spectrum le = emission_;
  if (texture_) le *= Spectrum(texture_->sample(uv));
  return le;
}

Spectrum Light::intensity(const Vec3& w) const {
  switch (type_) {
    case LightType::Point:
      return emission_;
    case LightType::Spot:
      return emission_ * spotFalloff(glm::dot(n_, w), cosInner_, cosOuter_);
    default:
      return Spectrum(0.f);
  }
}

Spectrum Light::power() const {
  switch (type_) {
    case LightType::Area: {
      // Phi = pi A <Le>: a Lambertian emitter radiates pi L per unit area on each emitting side,
      // <Le> the mean of radiance() over the triangle, which sampleLe's positions are uniform on.
      return meanLe_ * (kPi * area_ * (twoSided_ ? 2.f : 1.f));
    }
    case LightType::Point:
      return emission_ * (4.f * kPi);
    case LightType::Spot:
      // The exact integral of the KHR falloff (not pbrt's cone-midpoint approximation), so that
      // power-proportional selection and the light-tracing normalisation see the true flux.
      return emission_ * static_cast<float>(spotFalloffIntegral(cosInner_, cosOuter_));
    case LightType::Directional:
      return emission_ * (kPi * sqr(bounds_.radius));
    case LightType::Environment:
      return environment_->power();
  }
  return Spectrum(0.f);
}

LightBounds Light::lightBounds() const {
  LightBounds b;
  switch (type_) {
    case LightType::Area:
      b.lo = glm::min(p_[0], glm::min(p_[1], p_[2]));
      b.hi = glm::max(p_[0], glm::max(p_[1], p_[2]));
      b.phi = luminance(meanLe_) * kPi * area_;  // one side: a point sees one side of it
      b.w = n_;
      b.cosThetaO = 1.f;
      b.cosThetaE = 0.f;  // Lambertian: up to pi / 2 from the normal
      b.twoSided = twoSided_;
      break;
    case LightType::Point:
      b.lo = b.hi = p_[0];
      b.phi = luminance(emission_) * kPi;
      b.cosThetaO = -1.f;  // every direction
      b.cosThetaE = 0.f;
      break;
    case LightType::Spot:
      // Full intensity inside the inner cone, falling to zero at the outer one (pbrt-v4 SpotLight).
      b.lo = b.hi = p_[0];
      b.phi = luminance(emission_) * kPi;
      b.w = n_;
      // theta_e widened by 1e-3: with equal cones (a hard edge) cos(0) = 1 would refuse every
      // receiver, even inside the cone (importance needs cos(theta') > cos(theta_e)), and the
      // margin keeps the float comparison conservative just inside the outer cone.
      b.cosThetaO = cosInner_;
      b.cosThetaE = std::cos(std::max(0.f, std::acos(std::clamp(cosOuter_, -1.f, 1.f)) -
                                               std::acos(std::clamp(cosInner_, -1.f, 1.f))) +
                             1e-3f);
      break;
    case LightType::Directional:
    case LightType::Environment:
      break;  // at infinity: phi 0
  }
  if (!(b.phi > 0.f) || !std::isfinite(b.phi)) b.phi = 0.f;
  return b;
}

float Light::infiniteImportance() const {
  switch (type_) {
    case LightType::Directional: return kPi * luminance(emission_);
    // power / (pi r^2) is the integral of L over the sphere; a quarter of it, times pi.
    case LightType::Environment: return 0.25f * luminance(environment_->power()) / sqr(environment_->radius());
    default: return 0.f;
  }
}

}  // namespace pathlab
