#include "core/media/equiangular.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab {

std::optional<EquiangularSegment> equiangularSegment(const Vec3& o, const Vec3& d, float tMax, const Vec3& c) {
  if (!(tMax > 0.f)) return std::nullopt;
  EquiangularSegment s;
  s.delta = glm::dot(c - o, d);
  s.D = glm::length(o + s.delta * d - c);
  const float scale = std::abs(s.delta) + glm::length(c - o);
  if (!(s.D > 1e-6f * scale) || !std::isfinite(s.D)) return std::nullopt;
  s.tMax = tMax;
  s.L2 = glm::dot(c - o, c - o);
  // phi(tMax); an unbounded segment (a ray that escapes a medium filling space) subtends its limit.
  s.phiMax = std::isfinite(tMax) ? std::atan2(tMax * s.D, s.L2 - tMax * s.delta) : std::atan2(s.D, -s.delta);
  if (!(s.phiMax > 0.f)) return std::nullopt;
  return s;
}

float sampleEquiangular(const EquiangularSegment& s, float u) {
  const float phi = u * s.phiMax;
  const float sinPhi = std::sin(phi), cosPhi = std::cos(phi);
  // Toward the end of an unbounded segment the denominator reaches 0: held inside the segment.
  const float t = s.L2 * sinPhi / (s.D * cosPhi + s.delta * sinPhi);
  return std::isfinite(t) ? std::clamp(t, 0.f, std::min(s.tMax, std::numeric_limits<float>::max()))
                          : std::min(s.tMax, std::numeric_limits<float>::max());
}

float equiangularPdf(const EquiangularSegment& s, float t) {
  if (!(t >= 0.f && t <= s.tMax)) return 0.f;
  const float x = t - s.delta;
  return s.D / (s.phiMax * (s.D * s.D + x * x));
}

float equiangularCdf(const EquiangularSegment& s, float t) {
  if (!(t > 0.f)) return 0.f;
  if (!(t < s.tMax)) return 1.f;
  return std::atan2(t * s.D, s.L2 - t * s.delta) / s.phiMax;
}

}  // namespace pathlab
