// Tangent generation from uv derivatives, MikkTSpace-style (see tangents.h).
#include "core/scene/tangents.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

Vec3 orthogonalTangent(const Vec3& n, const Vec3& tangent) {
  const Vec3 t = tangent - n * glm::dot(n, tangent);
  const float len = glm::length(t);
  if (len > 1e-12f && std::isfinite(len)) return t / len;
  // Frisvad-style fallback: a unit vector perpendicular to n (Duff et al. 2017, "Building an
  // orthonormal basis, revisited").
  const float sign = std::copysign(1.f, n.z);
  const float a = -1.f / (sign + n.z);
  return Vec3(1.f + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x);
}

std::vector<Vec4> generateTangents(const std::vector<Vec3>& positions,
                                   const std::vector<Vec3>& normals, const std::vector<Vec2>& uvs,
                                   const std::vector<uint32_t>& indices) {
  const size_t n = positions.size();
  std::vector<Vec3> sum(n, Vec3(0.f));
  std::vector<float> handedness(n, 0.f);
  for (size_t t = 0; !uvs.empty() && t + 2 < indices.size(); t += 3) {
    const uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
    const Vec3 e1 = positions[i[1]] - positions[i[0]], e2 = positions[i[2]] - positions[i[0]];
    const Vec2 d1 = uvs[i[1]] - uvs[i[0]], d2 = uvs[i[2]] - uvs[i[0]];
    const float det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 0.f) || !std::isfinite(det)) continue;
    // Solve [e1 e2] = [dp/du dp/dv] [d1 d2] for the two derivatives.
    const Vec3 dpdu = (e1 * d2.y - e2 * d1.y) / det;
    const Vec3 dpdv = (e2 * d1.x - e1 * d2.x) / det;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = i[k];
      const Vec3 a = positions[i[(k + 1) % 3]] - positions[v];
      const Vec3 b = positions[i[(k + 2) % 3]] - positions[v];
      const float la = glm::length(a), lb = glm::length(b);
      if (!(la > 0.f && lb > 0.f)) continue;
      const float angle = std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.f, 1.f));
      const Vec3 projected = dpdu - normals[v] * glm::dot(normals[v], dpdu);
      const float len = glm::length(projected);
      if (!(len > 0.f) || !std::isfinite(len)) continue;
      sum[v] += angle * projected / len;
      // The normal map's +y is -dp/dv (v runs down the image in glTF).
      const float side = glm::dot(glm::cross(normals[v], dpdu), -dpdv);
      handedness[v] += angle * (side < 0.f ? -1.f : 1.f);
    }
  }
  std::vector<Vec4> out(n);
  for (size_t v = 0; v < n; ++v) {
    out[v] = Vec4(orthogonalTangent(normals[v], sum[v]), handedness[v] < 0.f ? -1.f : 1.f);
  }
  return out;
}

}  // namespace pathlab
