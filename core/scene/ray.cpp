// Robust ray-origin offsetting (Wächter and Binder 2019).
#include "core/scene/ray.h"

#include <bit>

namespace pathlab {

Vec3 offsetRayOrigin(const Vec3& p, const Vec3& n, const Vec3& dir) {
  // Constants from the paper: below kOrigin the float spacing is too fine for the integer
  // offset, so a small absolute offset takes over.
  constexpr float kOrigin = 1.f / 32.f;
  constexpr float kFloatScale = 1.f / 65536.f;
  constexpr float kIntScale = 256.f;
  const Vec3 nf = glm::dot(n, dir) < 0.f ? -n : n;
  Vec3 out;
  for (int i = 0; i < 3; ++i) {
    const auto ofi = static_cast<int32_t>(kIntScale * nf[i]);
    const int32_t bits = std::bit_cast<int32_t>(p[i]) + (p[i] < 0.f ? -ofi : ofi);
    out[i] = std::abs(p[i]) < kOrigin ? p[i] + kFloatScale * nf[i] : std::bit_cast<float>(bits);
  }
  return out;
}

}  // namespace pathlab
