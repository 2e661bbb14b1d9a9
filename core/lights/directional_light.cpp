// Directional lights: sampling and evaluation (directional_light.h).
#include "core/lights/directional_light.h"

#include "core/sampling/warp.h"

#include <algorithm>
#include <limits>

namespace pathlab {

DirectionalLight::DirectionalLight(const Vec3& direction, const Spectrum& irradiance, const SceneBounds& bounds)
    : E_(irradiance), n_(glm::normalize(direction)), frame_(n_), bounds_(bounds) {
  // An empty scene (radius 0) would make the disk pdf infinite.
  bounds_.radius = std::max(bounds.radius, 1e-3f);
}

LightLiSample DirectionalLight::sampleLi(const Vec3& ref, Vec2) const {
  LightLiSample s;
  s.wi = -n_;
  s.Li = E_;
  s.pdfW = 1.f;
  s.isDelta = true;
  s.pLight = ref - n_ * (2.f * bounds_.radius);
  s.dist = std::numeric_limits<float>::infinity();
  return s;
}

LightLeSample DirectionalLight::sampleLe(Vec2 uPos, Vec2) const {
  // pbrt-v3 DistantLight::Sample_Le: a disk covering the scene's bounding sphere, set back
  // by one radius so every ray starts outside the scene.
  LightLeSample s;
  const Vec2 d = sampleUniformDiskConcentric(uPos);
  const float r = bounds_.radius;
  const Vec3 pDisk = bounds_.center + r * (d.x * frame_.s + d.y * frame_.t);
  s.ray = Ray{pDisk - n_ * r, n_};
  s.n = n_;
  s.pdfPosA = 1.f / (kPi * r * r);
  s.pdfDirW = 1.f;
  s.Le = E_;
  return s;
}

EmissionPdf DirectionalLight::pdfLe(const Vec3&) const {
  // The disk covers the bounding sphere, so any point of the scene lies within it. The
  // direction is a delta; following pbrt's "remap zero to one", its density is 1.
  return EmissionPdf{1.f / (kPi * sqr(bounds_.radius)), 1.f};
}

Spectrum DirectionalLight::power() const { return E_ * (kPi * sqr(bounds_.radius)); }

float DirectionalLight::infiniteImportance() const { return kPi * luminance(E_); }

}  // namespace pathlab
