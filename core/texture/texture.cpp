// Texture lookup with glTF sampler semantics (wrap modes, NEAREST or bilinear magnification), the
// decoding of 8-bit texels, and the sRGB transfer functions.
#include "core/texture/texture.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace pathlab {
namespace {

// Wraps a texel index into [0, n) according to the glTF wrap mode.
int64_t wrapIndex(int64_t i, int64_t n, WrapMode mode) {
  switch (mode) {
    case WrapMode::ClampToEdge: return std::clamp<int64_t>(i, 0, n - 1);
    case WrapMode::MirroredRepeat: {
      const int64_t period = 2 * n;
      const int64_t m = ((i % period) + period) % period;
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

// 8-bit value -> linear float, one table per encoding: the values are those the loader computed
// when it stored float texels (v / 255, and the sRGB decode of v / 255), so lookups are unchanged.
using ByteTable = std::array<float, 256>;
const ByteTable& linearTable() {
  static const ByteTable table = [] {
    ByteTable t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = float(i) / 255.f;
    return t;
  }();
  return table;
}
const ByteTable& srgbTable() {
  static const ByteTable table = [] {
    ByteTable t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.f);
    return t;
  }();
  return table;
}

}  // namespace

bool Texture::valid() const {
  if (width <= 0 || height <= 0) return false;
  const size_t count = size_t(width) * size_t(height);
  if (bytes) return channels >= 1 && channels <= 4 && bytes->size() >= count * size_t(channels);
  return texels.size() >= count;
}

Vec4 Texture::fetch(int64_t x, int64_t y) const {
  const size_t index = size_t(wrapIndex(y, height, wrapT)) * size_t(width) + size_t(wrapIndex(x, width, wrapS));
  if (!bytes) return texels[index];
  const uint8_t* t = bytes->data() + index * size_t(channels);
  const ByteTable& linear = linearTable();
  const ByteTable& colour = srgb ? srgbTable() : linear;
  switch (channels) {
    case 1: return Vec4(Vec3(colour[t[0]]), 1.f);
    case 2: return Vec4(Vec3(colour[t[0]]), linear[t[1]]);
    case 3: return Vec4(colour[t[0]], colour[t[1]], colour[t[2]], 1.f);
    default: return Vec4(colour[t[0]], colour[t[1]], colour[t[2]], linear[t[3]]);
  }
}

Vec4 Texture::sampleImage(Vec2 uv) const {
  if (!valid()) return Vec4(0.f);
  double u = reduceCoordinate(uv.x, wrapS);
  double v = reduceCoordinate(uv.y, wrapT);
  if (nearest) {
    return fetch(int64_t(std::floor(u * width)), int64_t(std::floor(v * height)));
  }
  // Texel centres sit at half-integer coordinates (OpenGL / glTF convention). Filtering mixes
  // the decoded (linear) values, as the loader's float texels were mixed before.
  double x = u * width - 0.5, y = v * height - 0.5;
  double x0 = std::floor(x), y0 = std::floor(y);
  float fx = float(x - x0), fy = float(y - y0);
  const auto ix = int64_t(x0), iy = int64_t(y0);
  Vec4 top = glm::mix(fetch(ix, iy), fetch(ix + 1, iy), fx);
  Vec4 bottom = glm::mix(fetch(ix, iy + 1), fetch(ix + 1, iy + 1), fx);
  return glm::mix(top, bottom, fy);
}

Vec4 Texture::average() const {
  if (!valid()) return Vec4(0.f);
  glm::dvec4 sum(0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) sum += glm::dvec4(fetch(x, y));
  return Vec4(sum / (double(width) * double(height)));
}

size_t Texture::texelBytes() const {
  return bytes ? bytes->size() : texels.size() * sizeof(Vec4);
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
