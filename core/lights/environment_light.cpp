// Environment light: map lookup, importance sampling of directions and emission (see the header).
#include "core/lights/environment_light.h"

#include "core/sampling/warp.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

namespace {

constexpr float kTwoPiSquared = 2.f * kPi * kPi;

}  // namespace

EnvironmentLight::EnvironmentLight(const EnvironmentDesc& desc, const Vec3& center, float radius)
    : center_(center), radius_(std::max(radius, 1e-3f)) {
  const float angle = desc.rotationDegrees * (kPi / 180.f);
  cosRotation_ = std::cos(angle);
  sinRotation_ = std::sin(angle);
  if (desc.isConstant()) {
    constant_ = desc.constant * desc.strength;
    integral_ = constant_ * (4.f * kPi);
    return;
  }
  width_ = desc.width;
  height_ = desc.height;
  texels_.resize(desc.texels.size());
  std::vector<float> weights(desc.texels.size());
  glm::dvec3 integral(0.0);
  for (int y = 0; y < height_; ++y) {
    // A row spans theta in [y, y + 1] pi / height: its solid angle per texel is
    // (2 pi / width) (cos theta0 - cos theta1); its weight's sin(theta) is the row centre's, which
    // only shapes the density: pdfDirection divides by the exact sin(theta) of each direction.
    const double theta0 = kPi * y / height_, theta1 = kPi * (y + 1) / height_;
    const double texelSolidAngle = 2.0 * kPi / width_ * (std::cos(theta0) - std::cos(theta1));
    const float sinTheta = std::sin(kPi * (static_cast<float>(y) + 0.5f) / static_cast<float>(height_));
    for (int x = 0; x < width_; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x);
      texels_[i] = glm::max(desc.texels[i], Spectrum(0.f)) * desc.strength;
      weights[i] = luminance(texels_[i]) * sinTheta;
      integral += glm::dvec3(texels_[i]) * texelSolidAngle;
    }
  }
  integral_ = Spectrum(integral);
  distribution_ = PiecewiseConstant2D(weights, width_, height_);
}

Vec2 EnvironmentLight::toMap(const Vec3& w) const {
  float sinTheta = 0.f;
  return toMap(w, &sinTheta);
}

Vec2 EnvironmentLight::toMap(const Vec3& w, float* sinTheta) const {
  // Into the map's frame: turn by -rotation about +y.
  const Vec3 m(cosRotation_ * w.x - sinRotation_ * w.z, w.y, sinRotation_ * w.x + cosRotation_ * w.z);
  // theta from atan2, not acos(y): acos loses the angle near the poles, where sin(theta) divides
  // the density.
  *sinTheta = std::sqrt(m.x * m.x + m.z * m.z);
  const float theta = std::atan2(*sinTheta, m.y);
  const float phi = std::atan2(m.x, -m.z);
  float u = 0.5f + phi * kInv2Pi;
  u = u >= 1.f ? 0.f : u;
  return {u, theta * kInvPi};
}

Vec3 EnvironmentLight::fromMap(Vec2 uv) const {
  const float theta = uv.y * kPi, phi = (uv.x - 0.5f) * 2.f * kPi;
  const float sinTheta = std::sin(theta);
  const Vec3 m(sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi));
  return {cosRotation_ * m.x + sinRotation_ * m.z, m.y, -sinRotation_ * m.x + cosRotation_ * m.z};
}

Spectrum EnvironmentLight::Le(const Vec3& w) const {
  if (isConstant()) return constant_;
  // Nearest texel: the radiance is constant over each texel, as the sampling density is, so a
  // texel's density is zero exactly where its radiance is.
  const Vec2 uv = toMap(w);
  const int x = std::clamp(static_cast<int>(uv.x * static_cast<float>(width_)), 0, width_ - 1);
  const int y = std::clamp(static_cast<int>(uv.y * static_cast<float>(height_)), 0, height_ - 1);
  return texels_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
}

EnvironmentDirection EnvironmentLight::sampleDirection(Vec2 u) const {
  EnvironmentDirection d;
  if (isConstant()) {
    d.w = sampleUniformSphere(u);
    d.pdfW = uniformSpherePdf();
    return d;
  }
  float pdfMap = 0.f;
  const Vec2 uv = distribution_.sample(u, &pdfMap);
  const float sinTheta = std::sin(uv.y * kPi);
  if (!(pdfMap > 0.f) || !(sinTheta > 0.f)) return d;
  d.w = fromMap(uv);
  d.pdfW = pdfMap / (kTwoPiSquared * sinTheta);
  return d;
}

float EnvironmentLight::pdfDirection(const Vec3& w) const {
  if (isConstant()) return uniformSpherePdf();
  float sinTheta = 0.f;
  const Vec2 uv = toMap(w, &sinTheta);
  if (!(sinTheta > 0.f)) return 0.f;
  return distribution_.pdf(uv) / (kTwoPiSquared * sinTheta);
}

Vec3 EnvironmentLight::diskPoint(const Vec3& w, Vec2 u) const {
  const Frame frame(w);
  const Vec2 d = sampleUniformDiskConcentric(u);
  return center_ + radius_ * (d.x * frame.s + d.y * frame.t + w);
}

Spectrum EnvironmentLight::power() const { return integral_ * (kPi * radius_ * radius_); }

}  // namespace pathlab
