// Texture lookup with glTF sampler semantics (wrap modes, NEAREST or bilinear magnification)
// and the sRGB transfer functions used to decode colour textures at load time.
#include "core/texture/texture.h"

#include <algorithm>
#include <cmath>

namespace pathlab {
namespace {

// Wraps an integer texel index into [0, n) according to the glTF wrap mode. Callers keep i within
// a few periods of [0, n), so the modulo never sees an overflowed value.
int wrapIndex(int i, int n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge: return std::clamp(i, 0, n - 1);
    case WrapMode::MirroredRepeat: {
      int period = 2 * n;
      int m = ((i % period) + period) % period;
      return m < n ? m : period - 1 - m;
    }
    case WrapMode::Repeat:
    default: return ((i % n) + n) % n;
  }
}

// Reduces a texture coordinate to a bounded range with the same wrapped result, so that huge or
// non-finite coordinates cannot overflow the integer texel index (float -> int of an out-of-range
// value is undefined behaviour).
double reduceCoordinate(float u, WrapMode mode) {
  double d = std::isfinite(u) ? double(u) : 0.0;
  switch (mode) {
    case WrapMode::ClampToEdge: return std::clamp(d, 0.0, 1.0);
    case WrapMode::MirroredRepeat: return d - 2.0 * std::floor(d * 0.5);
    case WrapMode::Repeat:
    default: return d - std::floor(d);
  }
}

}  // namespace

Vec4 Texture::sample(Vec2 uv) const {
  if (width <= 0 || height <= 0 || texels.size() < size_t(width) * size_t(height)) return Vec4(0.f);
  double u = reduceCoordinate(uv.x, wrapS);
  double v = reduceCoordinate(uv.y, wrapT);
  auto texel = [&](int x, int y) -> const Vec4& {
    return texels[size_t(wrapIndex(y, height, wrapT)) * size_t(width) +
                  size_t(wrapIndex(x, width, wrapS))];
  };
  if (nearest) {
    return texel(int(std::floor(u * width)), int(std::floor(v * height)));
  }
  // Texel centres sit at half-integer coordinates (OpenGL / glTF convention).
  double x = u * width - 0.5, y = v * height - 0.5;
  double x0 = std::floor(x), y0 = std::floor(y);
  float fx = float(x - x0), fy = float(y - y0);
  int ix = int(x0), iy = int(y0);
  Vec4 top = glm::mix(texel(ix, iy), texel(ix + 1, iy), fx);
  Vec4 bottom = glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx);
  return glm::mix(top, bottom, fy);
}

Vec4 Texture::average() const {
  if (texels.empty()) return Vec4(0.f);
  glm::dvec4 sum(0.0);
  for (const Vec4& t : texels) sum += glm::dvec4(t);
  return Vec4(sum / double(texels.size()));
}

float srgbToLinear(float v) {
  if (v <= 0.04045f) return v / 12.92f;
  return std::pow((v + 0.055f) / 1.055f, 2.4f);
}

float linearToSrgb(float v) {
  if (v <= 0.0031308f) return 12.92f * v;
  return 1.055f * std::pow(v, 1.f / 2.4f) - 0.055f;
}

}  // namespace pathlab
