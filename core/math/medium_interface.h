// Which medium lies on either side of a surface (pbrt-v4 MediumInterface).
#pragma once

#include "core/math/types.h"

#include <cstdint>

namespace pathlab {

// The media on the two sides of a surface: on the side its geometric normal points to (outside)
// and on the other (inside), so that a ray leaving a surface point knows the medium it travels in
// from its direction alone (pbrt-v4 MediumInterface). -1: no medium.
struct MediumInterface {
  int16_t inside = -1;
  int16_t outside = -1;
  int toward(const Vec3& ng, const Vec3& w) const { return glm::dot(w, ng) < 0.f ? inside : outside; }
};

}  // namespace pathlab
