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
};

// Wächter and Binder 2019, "A Fast and Robust Method for Avoiding Self-Intersection" (Ray Tracing
// Gems, ch. 6): move p off the surface along the normal by a few ulps of its own magnitude, so the
// offset scales with the scene instead of a fixed epsilon. `n` is flipped toward `dir`.
Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n, const Vec3& dir);

}  // namespace pathlab
