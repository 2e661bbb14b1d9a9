// Equiangular sampling (Kulla and Fajardo 2012, "Importance sampling techniques for path tracing
// in participating media", sec. 4): a point x(t) = o + t d on a ray segment [0, tMax] chosen with
// density proportional to 1 / |x(t) - c|^2, the inverse square falloff of the light at c. With
// delta = (c - o) . d the foot of the perpendicular from c and D = |o + delta d - c| its length,
// t = delta + D tan(theta), theta uniform between theta_a = atan(-delta / D) and theta_b =
// atan((tMax - delta) / D), so
//     p(t) = D / ((theta_b - theta_a) (D^2 + (t - delta)^2)).
// In floats both angles lie near -pi/2 when the light is far past the segment's end, and their
// difference loses its digits; so the code keeps the angle from t = 0 instead, phi = theta -
// theta_a, in which (tangent addition, L^2 = D^2 + delta^2 = |c - o|^2)
//     phi(t) = atan2(t D, L^2 - t delta),   t(phi) = L^2 sin(phi) / (D cos(phi) + delta sin(phi)),
// both exact to a few ulps at any angle (the denominator is L cos(theta) > 0).
// Distance sampling (medium.h) follows the transmittance instead, and misses the light's
// neighbourhood in a thin medium; MIS combines the two (core/pt/path_tracer.cpp).
#pragma once

#include "core/math/types.h"

#include <optional>

namespace pathlab {

struct EquiangularSegment {
  float delta = 0.f;   // t of the point of the line closest to c
  float D = 0.f;       // its distance to c
  float L2 = 0.f;      // |c - o|^2
  float phiMax = 0.f;  // theta_b - theta_a, the angle the segment subtends at c, in (0, pi)
  float tMax = 0.f;
};

// The segment [0, tMax] (tMax may be infinite) of the ray (o, d), d unit, seen from c. Empty when
// c lies on the ray's line (D below a millionth of the distances involved): the density would be a
// spike no float resolves, and equiangular sampling declines that light point (its density is then
// zero for the MIS weights too, so the other technique keeps those paths).
std::optional<EquiangularSegment> equiangularSegment(const Vec3& o, const Vec3& d, float tMax, const Vec3& c);

// t in [0, tMax] with density equiangularPdf, from u in [0, 1).
float sampleEquiangular(const EquiangularSegment& s, float u);
// The density per unit length of sampleEquiangular choosing t (0 outside [0, tMax]).
float equiangularPdf(const EquiangularSegment& s, float t);
// Its distribution function, for the tests: the share of the samples at most t.
float equiangularCdf(const EquiangularSegment& s, float t);

}  // namespace pathlab
