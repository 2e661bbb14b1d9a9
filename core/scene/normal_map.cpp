// Normal mapping (see normal_map.h).
#include "core/scene/normal_map.h"

#include "core/scene/tangents.h"

#include <cmath>

namespace pathlab {

Vec3 mappedNormal(const Material& m, const ShadingInputs& at, const Vec3& n, const Vec4& tangent,
                  const std::vector<Texture>& textures) {
  if (!m.normalTexture.valid() || size_t(m.normalTexture.texture) >= textures.size()) return n;
  const Vec4 texel = textures[size_t(m.normalTexture.texture)].sample(at.uv(m.normalTexture));
  Vec3 c = 2.f * Vec3(texel) - 1.f;
  c.x *= m.normalScale;
  c.y *= m.normalScale;
  const Vec3 t = orthogonalTangent(n, Vec3(tangent));
  const Vec3 b = (tangent.w < 0.f ? -1.f : 1.f) * glm::cross(n, t);
  const Vec3 mapped = c.x * t + c.y * b + c.z * n;
  const float len = glm::length(mapped);
  return len > 1e-6f && std::isfinite(len) ? mapped / len : n;
}

}  // namespace pathlab
