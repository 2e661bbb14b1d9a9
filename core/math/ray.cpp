// Robust ray-origin offsetting from floating-point error bounds (Pharr, Jakob, Humphreys, pbrt-v4,
// sec. 6.8).
#include "core/math/ray.h"

#include <bit>
#include <cmath>
#include <cstdint>

namespace pathlab {

namespace {
// gamma(n) = n eps / (1 - n eps), eps = 2^-24 (pbrt-v4 eq. 6.31).
constexpr float gamma(int n) {
  constexpr float eps = 0x1p-24f;
  return static_cast<float>(n) * eps / (1.f - static_cast<float>(n) * eps);
}
constexpr float kOffsetSafety = 32.f;

// std::nextafter(v, +inf) / (v, -inf) by stepping the bit pattern (pbrt-v4 NextFloatUp /
// NextFloatDown): the same result for every input, NaN and infinities included, without the
// libm call, which cost a visible share of every ray (three per origin, two origins per shadow ray).
float nextFloatUp(float v) {
  if (!(v < std::numeric_limits<float>::infinity())) return v;  // +inf and NaN stay
  if (v == 0.f) return std::numeric_limits<float>::denorm_min();  // from +0 and -0 alike
  auto bits = std::bit_cast<uint32_t>(v);
  bits = v > 0.f ? bits + 1 : bits - 1;  // toward +inf in value: magnitude up if positive, down if negative
  return std::bit_cast<float>(bits);
}
float nextFloatDown(float v) { return -nextFloatUp(-v); }
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
    if (offset[i] > 0.f) po[i] = nextFloatUp(po[i]);
    else if (offset[i] < 0.f) po[i] = nextFloatDown(po[i]);
  }
  return po;
}

}  // namespace pathlab
