// Vector, colour and constant vocabulary shared by all of pathlab (GLM underneath).
#pragma once

#include <glm/glm.hpp>

#include <cmath>
#include <cstdint>

namespace pathlab {

using Vec2 = glm::vec2;
using Vec3 = glm::vec3;
using Vec4 = glm::vec4;
using Mat3 = glm::mat3;
using Mat4 = glm::mat4;
using DVec3 = glm::dvec3;
using Vec2i = glm::ivec2;
// RGB radiometric quantity (radiance, importance, throughput). pathlab is an RGB renderer.
using Spectrum = glm::vec3;

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;
inline constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

inline float luminance(const Spectrum& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }
inline float maxComponent(const Spectrum& c) { return glm::max(c.r, glm::max(c.g, c.b)); }
inline bool isBlack(const Spectrum& c) { return c.r == 0.f && c.g == 0.f && c.b == 0.f; }
inline bool isFinite(const Spectrum& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}
// A contribution the film may accept: finite and non-negative in every channel.
inline bool isValidContribution(const Spectrum& c) {
  return isFinite(c) && c.r >= 0.f && c.g >= 0.f && c.b >= 0.f;
}

inline float absDot(const Vec3& a, const Vec3& b) { return std::abs(glm::dot(a, b)); }
inline float sqr(float x) { return x * x; }
inline float safeSqrt(float x) { return std::sqrt(glm::max(x, 0.f)); }

}  // namespace pathlab
