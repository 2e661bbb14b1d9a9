// A directional light (KHR_lights_punctual "directional", the sun): irradiance from one direction
// at infinity, a delta in direction. Emitted rays start on a disk covering the scene's bounding
// sphere (pbrt-v3 DistantLight), whose area is its position density.
#pragma once

#include "core/lights/emitter.h"
#include "core/math/frame.h"

namespace pathlab {

class DirectionalLight {
 public:
  static constexpr LightType kType = LightType::Directional;

  DirectionalLight(const Vec3& direction, const Spectrum& irradiance, const SceneBounds& bounds);

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  EmissionPdf pdfLe(const Vec3& dir) const;
  // The irradiance through the bounding disk.
  Spectrum power() const;
  LightBounds lightBounds() const { return {}; }  // at infinity: phi 0
  // pi E: the light's weight against a BVH's importance (light.h).
  float infiniteImportance() const;

 private:
  Spectrum E_{0.f};
  Vec3 n_{0.f};  // direction of travel
  Frame frame_;
  SceneBounds bounds_;
};

}  // namespace pathlab
