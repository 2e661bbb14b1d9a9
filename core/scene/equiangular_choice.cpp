#include "core/scene/equiangular_choice.h"

#include "core/media/equiangular.h"

namespace pathlab {

std::optional<EquiangularChoice> chooseEquiangularVertex(const Scene& scene, const Vec3& origin, const Vec3& direction,
                                                         float tMax, Pcg32& rng) {
  const LightSet& lights = scene.lights();
  EquiangularChoice c;
  const float uLight = rng.next1D();
  c.uPos = rng.next2D();
  const float uT = rng.next1D();
  c.light = lights.sampleNee(LightSampleContext{origin, Vec3(0.f)}, uLight, &c.pmf);
  if (c.light < 0 || !(c.pmf > 0.f)) return std::nullopt;
  const Light& light = lights[static_cast<size_t>(c.light)];
  if (light.isInfinite()) return std::nullopt;
  const LightLiSample fromOrigin = light.sampleLi(origin, c.uPos);
  if (!(fromOrigin.dist > 0.f)) return std::nullopt;
  const std::optional<EquiangularSegment> eq = equiangularSegment(origin, direction, tMax, fromOrigin.pLight);
  if (!eq) return std::nullopt;
  c.t = sampleEquiangular(*eq, uT);
  c.pdfT = equiangularPdf(*eq, c.t);
  return c;
}

}  // namespace pathlab
