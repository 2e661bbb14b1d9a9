// Orthonormal shading frame: world <-> local with the normal as +z.
#pragma once

#include "core/math/types.h"

namespace pathlab {

struct Frame {
  Vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

  Frame() = default;
  // Duff et al. 2017, "Building an Orthonormal Basis, Revisited" (branchless, no singularity).
  explicit Frame(const Vec3& normal) : n(normal) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float b = n.x * n.y * a;
    s = Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    t = Vec3(b, sign + n.y * n.y * a, -n.y);
  }
  Vec3 toLocal(const Vec3& v) const { return {glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)}; }
  Vec3 toWorld(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace pathlab
