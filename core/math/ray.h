// Rays, surface hits and robust ray-origin offsetting.
#pragma once

#include "core/math/types.h"
#include "core/math/medium_interface.h"

#include <bit>
#include <cstdint>
#include <limits>

namespace pathlab {

struct Ray {
  Vec3 o{0.f};
  Vec3 d{0.f, 0.f, 1.f};
  float tMax = std::numeric_limits<float>::infinity();
};

struct SurfaceHit {
  Vec3 p{0.f};
  Vec3 ng{0.f, 0.f, 1.f};  // geometric normal from the triangle's winding (unit)
  Vec3 ns{0.f, 0.f, 1.f};  // shading normal (unit; interpolated, normal-mapped), in ng's hemisphere
  Vec2 uv{0.f};            // TEXCOORD_0
  Vec2 uv1{0.f};           // TEXCOORD_1
  Spectrum color{1.f};     // COLOR_0 (rgb), 1 without vertex colours
  float t = 0.f;
  uint32_t meshId = 0, primId = 0;
  int material = 0;
  int light = -1;          // index into the scene's LightSet when the triangle emits
  Vec3 pError{0.f};        // bound on |p - exact point| per component (interpolationError)
  // Scenes with media only (Scene::hasMedia): the media on either side of the triangle, and
  // whether it is an index-matched boundary rays pass through (core/scene/scene_media.h).
  MediumInterface media;
  bool indexMatched = false;
};

// Conservative bound on the rounding error of p = b0 p0 + b1 p1 + b2 p2 per component: pbrt-v4's
// gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|) (sec. 6.8.5), widened by kOffsetSafety because Embree's
// own intersection test, not pbrt's, decides whether a ray leaving p hits its triangle again.
// Proportional to the coordinates' magnitudes, so the offset scales with the scene: a scene
// modelled in micrometres or kilometres self-intersects no more than one in metres.
// Inline, with offsetRayOrigin: every walk vertex and every shadow ray's two ends use them (a call
// each was 2-3 % of a bidirectional sample).
[[gnu::always_inline]] inline Vec3 interpolationError(float b0, const Vec3& p0, float b1, const Vec3& p1, float b2, const Vec3& p2) {
  // gamma(n) = n eps / (1 - n eps), eps = 2^-24 (pbrt-v4 eq. 6.31).
  constexpr float eps = 0x1p-24f;
  constexpr float gamma7 = 7.f * eps / (1.f - 7.f * eps);
  constexpr float kOffsetSafety = 32.f;
  return (kOffsetSafety * gamma7) * (glm::abs(b0 * p0) + glm::abs(b1 * p1) + glm::abs(b2 * p2));
}

// std::nextafter(v, +inf) by stepping the bit pattern (pbrt-v4 NextFloatUp): the same result for
// every input, NaN and infinities included, without the libm call.
[[gnu::always_inline]] inline float nextFloatUp(float v) {
  if (!(v < std::numeric_limits<float>::infinity())) return v;  // +inf and NaN stay
  if (v == 0.f) return std::numeric_limits<float>::denorm_min();  // from +0 and -0 alike
  auto bits = std::bit_cast<uint32_t>(v);
  bits = v > 0.f ? bits + 1 : bits - 1;  // toward +inf in value: magnitude up if positive, down if negative
  return std::bit_cast<float>(bits);
}
// std::nextafter(v, -inf).
[[gnu::always_inline]] inline float nextFloatDown(float v) { return -nextFloatUp(-v); }

// po rounded one float further in the direction of offset (unchanged for a zero offset).
[[gnu::always_inline]] inline float offsetAway(float po, float offset) {
  return offset > 0.f ? nextFloatUp(po) : offset < 0.f ? nextFloatDown(po) : po;
}
// pbrt-v4 OffsetRayOrigin: p moved along n, on the side of `dir`, by dot(|n|, pError), then each
// coordinate rounded one float further away. A zero pError (camera, punctual light) leaves p.
// Forced inline: GCC kept it a call at -O2 despite `inline`, 4 % of a bidirectional sample's
// instructions.
[[gnu::always_inline]] inline Vec3 offsetRayOrigin(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& dir) {
  const float d = glm::dot(glm::abs(n), pError);
  Vec3 offset = d * n;
  if (glm::dot(dir, n) < 0.f) offset = -offset;
  const Vec3 po = p + offset;
  return Vec3(offsetAway(po.x, offset.x), offsetAway(po.y, offset.y), offsetAway(po.z, offset.z));
}

}  // namespace pathlab
