// The first steps of equiangular sampling toward a light (Kulla and Fajardo 2012), shared by the
// path tracer's technique B (core/pt/path_tracer.cpp) and BPT's technique family E(1, k)
// (core/bpt/equiangular_technique.h): a light and a point on it chosen with the ray's origin as the
// receiver (the vertex does not exist yet), then the vertex's distance along the ray with the
// equiangular density toward that point (core/media/equiangular.h).
#pragma once

#include "core/math/rng.h"
#include "core/scene/scene.h"

#include <optional>

namespace pathlab {

struct EquiangularChoice {
  int light = -1;
  float pmf = 0.f;    // next-event estimation's choice of the light, the ray's origin as receiver
  // The light point's numbers: an area light's points are uniform in area whoever the receiver,
  // so sampleLi(x, uPos) from the vertex x gives the same point (a punctual light's is its position).
  Vec2 uPos{0.f};
  float t = 0.f;      // the vertex's distance along the ray
  float pdfT = 0.f;   // its equiangular density per unit length
};

// Draws three numbers (light, point, distance) whatever happens, then chooses; empty when the
// light is at infinity (no point to aim at), the point is the origin or lies on the ray's line.
// tMax: the segment's end (infinite: the unbounded ray).
std::optional<EquiangularChoice> chooseEquiangularVertex(const Scene& scene, const Vec3& origin, const Vec3& direction,
                                                         float tMax, Pcg32& rng);

}  // namespace pathlab
