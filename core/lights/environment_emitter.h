// The environment as an emitter: the map (environment_light.h) seen as a light at infinity,
// sampled by direction, emitting from a disk covering the scene (pbrt-v4 ImageInfiniteLight).
#pragma once

#include "core/lights/emitter.h"
#include "core/lights/environment_light.h"

namespace pathlab {

class EnvironmentEmitter {
 public:
  static constexpr LightType kType = LightType::Environment;

  // `environment` must outlive the emitter (Scene owns both).
  explicit EnvironmentEmitter(const EnvironmentLight* environment) : environment_(environment) {}

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  // The position density is the disk's, the direction density the map's at -dir.
  EmissionPdf pdfLe(const Vec3& dir) const;
  Spectrum power() const { return environment_->power(); }
  LightBounds lightBounds() const { return {}; }  // at infinity: phi 0
  // pi x a quarter of the integral of L over the sphere (pi L for a uniform one: what a surface
  // facing up receives): the light's weight against a BVH's importance (light.h).
  float infiniteImportance() const;
  const EnvironmentLight* environment() const { return environment_; }

 private:
  const EnvironmentLight* environment_;
};

}  // namespace pathlab
