// Rays, surface hits and robust ray-origin offsetting.
#pragma once

#include "core/math/types.h"

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
  Vec3 ns{0.f, 0.f, 1.f};  // interpolated shading normal (unit), flipped into ng's hemisphere
  Vec2 uv{0.f};
  float t = 0.f;
  uint32_t meshId = 0, primId = 0;
  int material = 0;
  int light = -1;          // index into the scene's LightSet when the triangle emits
  Vec3 pError{0.f};        // bound on |p - exact point| per component (interpolationError)
};

// Conservative bound on the rounding error of p = b0 p0 + b1 p1 + b2 p2 per component: pbrt-v4's
// gamma(7) (|b0 p0| + |b1 p1| + |b2 p2|) (sec. 6.8.5), widened by kOffsetSafety because Embree's
// own intersection test, not pbrt's, decides whether a ray leaving p hits its triangle again.
// Proportional to the coordinates' magnitudes, so the offset scales with the scene: a scene
// modelled in micrometres or kilometres self-intersects no more than one in metres.
Vec3 interpolationError(float b0, const Vec3& p0, float b1, const Vec3& p1, float b2, const Vec3& p2);

// pbrt-v4 OffsetRayOrigin: p moved along n, on the side of `dir`, by dot(|n|, pError), then each
// coordinate rounded one float further away. A zero pError (camera, punctual light) leaves p.
Vec3 offsetRayOrigin(const Vec3& p, const Vec3& pError, const Vec3& n, const Vec3& dir);

}  // namespace pathlab
