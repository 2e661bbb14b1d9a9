// Per-vertex tangent frames for normal maps when the file has no TANGENT attribute.
#pragma once

#include "core/math/types.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// One tangent per vertex (xyz unit and perpendicular to the vertex normal, w = +-1 the
// handedness: bitangent = w cross(normal, tangent), glTF 2.0 sec. 3.7.2.1), built as MikkTSpace
// does (Mikkelsen 2008, "Simulation of wrinkled surfaces revisited", sec. 3-4): each triangle's
// tangent is the surface derivative dp/du from its uv derivatives; at each corner it is
// projected into the plane of the vertex normal, normalised and weighted by the corner's angle;
// the sums are normalised per vertex. glTF's v runs down the image (the normal map's +y is
// -dp/dv), which fixes the sign of the handedness. A vertex whose triangles have no uv
// derivative (collinear uvs, no uvs) gets an arbitrary tangent perpendicular to its normal.
std::vector<Vec4> generateTangents(const std::vector<Vec3>& positions,
                                   const std::vector<Vec3>& normals, const std::vector<Vec2>& uvs,
                                   const std::vector<uint32_t>& indices);

// `tangent` made perpendicular to unit `n` and unit (Gram-Schmidt), or any unit vector
// perpendicular to n when it has no component off n.
Vec3 orthogonalTangent(const Vec3& n, const Vec3& tangent);

}  // namespace pathlab
