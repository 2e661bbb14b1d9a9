// Normal mapping: the shading normal a glTF normalTexture gives a surface point.
#pragma once

#include "core/scene/material.h"

namespace pathlab {

// glTF 2.0 sec. 3.9.3: the texel (r, g, b) in [0, 1] is the tangent-space normal
// (2r - 1, 2g - 1, 2b - 1), x and y scaled by normalTexture.scale, in the frame (tangent,
// bitangent = w cross(n, tangent), n) of the interpolated normal `n` (unit) and tangent
// (xyz, w = handedness; made perpendicular to n here). Returns the unit mapped normal, or `n`
// when the material has no normal map or the mapped normal is degenerate.
Vec3 mappedNormal(const Material& m, const ShadingInputs& at, const Vec3& n, const Vec4& tangent,
                  const std::vector<Texture>& textures);

}  // namespace pathlab
