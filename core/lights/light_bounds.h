// The bounds a light BVH keeps per node (Conty Estevez and Kulla 2018, "Importance Sampling of
// Many Lights with Adaptive Tree Splitting"; pbrt-v4 LightBounds): a box around the emitters, their
// summed emission scale `phi`, and a cone bounding their normals (w, theta_o) widened by how far
// from its normal an emitter still emits (theta_e). `importance` bounds from above what the
// emitters inside can send to a receiving point, without looking at any one of them.
#pragma once

#include "core/math/types.h"

namespace pathlab {

// Where next-event estimation receives light: a surface point with its geometric normal, or a
// point in a medium (n = 0: every direction receives).
struct LightSampleContext {
  Vec3 p{0.f};
  Vec3 n{0.f};
};

struct LightBounds {
  Vec3 lo{0.f}, hi{0.f};
  // pi x the largest radiant intensity an emitter inside sends along its normal (area: pi L A;
  // point and spot: pi I), summed: so that phi cos / d^2 is pi x the irradiance it gives a
  // surface facing it at distance d, the scale infinite lights' importance is in (light.h).
  float phi = 0.f;
  Vec3 w{0.f, 0.f, 1.f};  // the normal cone's axis (the direction emitted light travels)
  float cosThetaO = 1.f;  // the normal cone's half-angle
  float cosThetaE = 0.f;  // how far past its normal an emitter emits (pi / 2 for Lambertian)
  bool twoSided = false;  // emits on both sides of its normal

  Vec3 centroid() const { return 0.5f * (lo + hi); }
  // An upper bound (up to the approximations of Conty and Kulla's eq. 3) of phi cos(theta') / d^2
  // x the receiver's cos(theta_i'): zero only where no emitter inside can light the point.
  float importance(const LightSampleContext& ctx) const;
};

// The smallest bounds holding both (pbrt-v4 Union of LightBounds and of DirectionCones).
LightBounds unionOf(const LightBounds& a, const LightBounds& b);

// The orientation measure M_Omega of Conty and Kulla's eq. 1, for the build's cost.
float orientationMeasure(const LightBounds& b);

}  // namespace pathlab
