// The environment light: radiance arriving from every direction at infinity, an equirectangular
// (latitude-longitude) map or a constant, importance-sampled in proportion to radiance x sin(theta)
// (pbrt-v3 InfiniteAreaLight, sec. 14.2.4; pbrt-v4 ImageInfiniteLight / UniformInfiniteLight).
//
// Map coordinates, for a direction w toward the environment, in the map's frame (the world turned
// by -rotation about +y): theta = acos(w.y) from straight up, phi = atan2(w.x, -w.z), and
// u = 1/2 + phi / (2 pi), v = theta / pi. The map's centre is straight ahead of a glTF camera
// (-z), its right half is +x, its top row is up. Since dw = sin(theta) dtheta dphi =
// 2 pi^2 sin(theta) du dv, a density p(u, v) on the map is p(u, v) / (2 pi^2 sin theta) in solid
// angle (pbrt-v3 eq. 14.9).
#pragma once

#include "core/lights/environment_desc.h"
#include "core/math/frame.h"
#include "core/sampling/distribution2d.h"

namespace pathlab {

struct EnvironmentDirection {
  Vec3 w{0.f};       // toward the environment
  float pdfW = 0.f;  // solid angle
};

class EnvironmentLight {
 public:
  // `center`, `radius`: the scene's bounding sphere, which the emission disk covers.
  EnvironmentLight(const EnvironmentDesc& desc, const Vec3& center, float radius);

  // Radiance arriving from direction w (unit, toward the environment), strength included.
  Spectrum Le(const Vec3& w) const;
  EnvironmentDirection sampleDirection(Vec2 u) const;
  float pdfDirection(const Vec3& w) const;

  // Emission into the scene (pbrt-v4 ImageInfiniteLight::SampleLe): a direction w from the map and
  // a point on the disk of the bounding sphere's radius through its centre, normal to w, set back
  // by one radius along w; the ray travels along -w. pdfPosA = 1 / (pi r^2), pdfDirW = pdfDirection(w).
  float pdfPosition() const { return 1.f / (kPi * radius_ * radius_); }
  Vec3 diskPoint(const Vec3& w, Vec2 u) const;

  // Flux through the bounding disk: pi r^2 x the integral of Le over the sphere (pbrt-v4 Phi).
  Spectrum power() const;
  float radius() const { return radius_; }
  bool isConstant() const { return width_ == 0; }

  // Map coordinates of a world direction and back (the map's rotation applied).
  Vec2 toMap(const Vec3& w) const;
  Vec3 fromMap(Vec2 uv) const;

 private:
  Vec2 toMap(const Vec3& w, float* sinTheta) const;  // sinTheta of the unit direction w
  int width_ = 0, height_ = 0;
  std::vector<Spectrum> texels_;  // strength included
  Spectrum constant_{0.f};        // strength included
  PiecewiseConstant2D distribution_;
  float cosRotation_ = 1.f, sinRotation_ = 0.f;
  Vec3 center_{0.f};
  float radius_ = 1.f;
  Spectrum integral_{0.f};  // integral of Le over the sphere
};

}  // namespace pathlab
