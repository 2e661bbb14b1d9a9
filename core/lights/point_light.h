// Punctual lights of KHR_lights_punctual: a point light, emitting alike in every direction, and a
// spot light, whose intensity falls off between an inner and an outer cone. Both are deltas in
// position: no ray hits them, and their position density is one ("remap zero to one").
#pragma once

#include "core/lights/emitter.h"
#include "core/math/frame.h"

namespace pathlab {

class PointLight {
 public:
  static constexpr LightType kType = LightType::Point;

  PointLight(const Vec3& position, const Spectrum& intensity) : position_(position), I_(intensity) {}

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  // Directions uniform on the sphere.
  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  EmissionPdf pdfLe(const Vec3& dir) const;
  // Radiant intensity toward w (used by sampleLe and connections): the same everywhere.
  Spectrum intensity(const Vec3& w) const;
  Spectrum power() const;  // 4 pi I
  LightBounds lightBounds() const;
  const Vec3& position() const { return position_; }

 private:
  Vec3 position_{0.f};
  Spectrum I_{0.f};
};

class SpotLight {
 public:
  static constexpr LightType kType = LightType::Spot;

  // Cone angles in radians (glTF's); the outer one at least kMinConeAngle, the inner one at most the outer.
  SpotLight(const Vec3& position, const Vec3& direction, const Spectrum& intensity, float innerConeAngle,
            float outerConeAngle);

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  // Directions uniform in the outer cone: the falloff is in Le, not in the density.
  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  EmissionPdf pdfLe(const Vec3& dir) const;
  // The KHR falloff: I along the axis and inside the inner cone, zero outside the outer one.
  Spectrum intensity(const Vec3& w) const;
  // The exact integral of the KHR falloff (not pbrt's cone-midpoint approximation), so that
  // power-proportional selection and the light-tracing normalisation see the true flux.
  Spectrum power() const;
  LightBounds lightBounds() const;
  const Vec3& position() const { return position_; }

 private:
  Vec3 position_{0.f};
  Spectrum I_{0.f};  // along the axis (inside the inner cone)
  Vec3 n_{0.f};      // the axis: direction of travel
  Frame frame_;
  float cosInner_ = 1.f, cosOuter_ = 0.f;
};

}  // namespace pathlab
