// Display transform of the viewer on the CPU: the reference for shaders/display.frag (tested) and
// the tone mapping of the technique pyramid's thumbnails.
#include "ui/display/display_settings.h"

#include "core/film/image_io.h"

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

namespace {

float srgbEncode(float c) {
  c = std::clamp(c, 0.f, 1.f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.f / 2.4f) - 0.055f;
}

}  // namespace

float displayValue(float linear, const DisplaySettings& settings) { return exposeToSrgb(linear, settings.exposure); }

Vec3 acesFilmic(const Vec3& x) {
  return glm::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), Vec3(0.f), Vec3(1.f));
}

// Turbo colour map, polynomial fit by Google (Mikhailov 2019); same coefficients as the shader.
Vec3 turbo(float t) {
  t = std::clamp(t, 0.f, 1.f);
  const Vec4 v4(1.f, t, t * t, t * t * t);
  const Vec2 v2 = Vec2(v4.z, v4.w) * v4.z;
  const Vec4 r4(0.13572138f, 4.61539260f, -42.66032258f, 132.13108234f);
  const Vec4 g4(0.09140261f, 2.19418839f, 4.84296658f, -14.18503333f);
  const Vec4 b4(0.10667330f, 12.64194608f, -60.58204836f, 110.36276771f);
  const Vec2 r2(-152.94239396f, 59.28637943f), g2(4.27729857f, 2.82956604f), b2(-89.90310912f, 27.34824973f);
  return {glm::dot(v4, r4) + glm::dot(v2, r2), glm::dot(v4, g4) + glm::dot(v2, g2), glm::dot(v4, b4) + glm::dot(v2, b2)};
}

float errorBarPosition(float error, const DisplaySettings& d) {
  if (d.errorLog) {
    if (!(error > 0.f)) return 0.f;
    return std::clamp((std::log10(error) - d.errorLogMin) / (d.errorLogMax - d.errorLogMin), 0.f, 1.f);
  }
  return std::clamp(error / d.errorLinearMax, 0.f, 1.f);
}

Vec3 errorColour(const Spectrum& image, const Spectrum& reference, const DisplaySettings& d) {
  Image x{1, 1, {image.r, image.g, image.b}}, r{1, 1, {reference.r, reference.g, reference.b}};
  return viridis(errorBarPosition(pixelErrors(x, r, d.errorKind)[0], d));
}

Vec3 displayColour(const Spectrum& radiance, const DisplaySettings& settings) {
  Vec3 L = radiance * std::exp2(settings.exposure);
  if (settings.falseColour) {
    const float Y = luminance(L);
    if (!(Y > 0.f) || std::log10(Y) < settings.logMin) return Vec3(0.f);
    return turbo((std::log10(Y) - settings.logMin) / (settings.logMax - settings.logMin));
  }
  if (settings.toneMap == ToneMap::Filmic) L = acesFilmic(L);
  return {srgbEncode(L.r), srgbEncode(L.g), srgbEncode(L.b)};
}

float autoExposure(const Image& image) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i + 2 < image.rgb.size(); i += 3) {
    const float Y = luminance({image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]});
    if (std::isfinite(Y)) sum += Y, ++n;
  }
  const double mean = n > 0 ? sum / static_cast<double>(n) : 0.0;
  if (!(mean > 1e-12)) return 0.f;
  return std::clamp(static_cast<float>(std::log2(0.18 / mean)), -20.f, 20.f);
}

std::vector<uint8_t> toRgba8(const Image& image, const DisplaySettings& settings) {
  std::vector<uint8_t> out(static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4);
  for (size_t p = 0; p < out.size() / 4; ++p) {
    const Vec3 c = displayColour({image.rgb[3 * p], image.rgb[3 * p + 1], image.rgb[3 * p + 2]}, settings);
    for (int k = 0; k < 3; ++k) out[4 * p + k] = static_cast<uint8_t>(std::lround(std::clamp(c[k], 0.f, 1.f) * 255.f));
    out[4 * p + 3] = 255;
  }
  return out;
}

}  // namespace pathlab::ui
