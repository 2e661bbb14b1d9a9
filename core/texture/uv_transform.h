// KHR_texture_transform: the affine map a texture applies to its coordinates before the lookup.
#pragma once

#include "core/math/types.h"

#include <cmath>

namespace pathlab {

// uv' = a u + b v + c, the 2x3 affine matrix by columns. Affine, so it commutes with barycentric
// interpolation: transforming a triangle's corner uvs transforms every point of it.
struct UvTransform {
  Vec2 a{1.f, 0.f}, b{0.f, 1.f}, c{0.f, 0.f};

  // KHR_texture_transform's matrix T * R * S (translation `offset`, `rotation` in radians
  // counter-clockwise in uv space as the extension's README writes R = [cos sin; -sin cos],
  // then `scale`), applied to column vectors (u, v, 1).
  static UvTransform fromGltf(Vec2 offset, float rotation, Vec2 scale) {
    const float cs = std::cos(rotation), sn = std::sin(rotation);
    UvTransform t;
    t.a = Vec2(cs * scale.x, -sn * scale.x);
    t.b = Vec2(sn * scale.y, cs * scale.y);
    t.c = offset;
    return t;
  }
  Vec2 apply(Vec2 uv) const { return a * uv.x + b * uv.y + c; }
  bool isIdentity() const { return *this == UvTransform{}; }
  bool operator==(const UvTransform&) const = default;
};

}  // namespace pathlab
