// The environment as an emitter: sampling and densities (environment_emitter.h).
#include "core/lights/environment_emitter.h"

#include <limits>

namespace pathlab {

LightLiSample EnvironmentEmitter::sampleLi(const Vec3& ref, Vec2 u) const {
  LightLiSample s;
  const EnvironmentDirection d = environment_->sampleDirection(u);
  if (!(d.pdfW > 0.f)) return s;
  s.wi = d.w;
  s.pdfW = d.pdfW;
  s.Li = environment_->Le(d.w);
  s.pLight = ref + d.w * (2.f * environment_->radius());
  s.dist = std::numeric_limits<float>::infinity();
  return s;
}

LightLeSample EnvironmentEmitter::sampleLe(Vec2 uPos, Vec2 uDir) const {
  // pbrt-v4 ImageInfiniteLight::SampleLe: the direction from the map, the origin on the disk.
  LightLeSample s;
  const EnvironmentDirection d = environment_->sampleDirection(uDir);
  if (!(d.pdfW > 0.f)) return s;
  s.ray = Ray{environment_->diskPoint(d.w, uPos), -d.w};
  s.n = -d.w;
  s.pdfPosA = environment_->pdfPosition();
  s.pdfDirW = d.pdfW;
  s.Le = environment_->Le(d.w);
  return s;
}

EmissionPdf EnvironmentEmitter::pdfLe(const Vec3& dir) const {
  return EmissionPdf{environment_->pdfPosition(), environment_->pdfDirection(-dir)};
}

float EnvironmentEmitter::infiniteImportance() const {
  // power / (pi r^2) is the integral of L over the sphere; a quarter of it, times pi.
  return 0.25f * luminance(environment_->power()) / sqr(environment_->radius());
}

}  // namespace pathlab
