// Robust ray-origin offsetting from floating-point error bounds (Pharr, Jakob, Humphreys, pbrt-v4,
// sec. 6.8).
#include "core/scene/ray.h"

#include <cmath>

namespace pathlab {

namespace {
// gamma(n) = n eps / (1 - n eps), eps = 2^-24 (pbrt-v4 eq. 6.31).
constexpr float gamma(int n) {
  constexpr float eps = 0x1p-24f;
  return static_cast<float>(n) * eps / (1.f - static_cast<float>(n) * eps);
}
constexpr float kOffsetSafety = 32.f;
}  // namespace

Vec3 interpolationError(float b0, const Vec3& p0, float b1, const Vec3& p1, float b2, const Vec3& p2) {
  return (kOffsetSafety * gamma(7)) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
}

Vec3 offsetRayOrigin(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& dir) {
  const float d = glm::dot(glm::abs(n), pError);
  Vec3 offset = d * n;
  if (glm::dot(dir, n) < 0.f) offset = -offset;
  Vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0.f) po[i] = std::nextafter(po[i], std::numeric_limits<float>::infinity());
    else if (offset[i] < 0.f) po[i] = std::nextafter(po[i], -std::numeric_limits<float>::infinity());
  }
  return po;
}

}  // namespace pathlab
