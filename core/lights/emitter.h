// What every kind of emitter provides (area_light.h, point_light.h, directional_light.h,
// environment_emitter.h), and the records it answers with. Path tracing and bidirectional path
// tracing ask a light for:
//  - sampleLi: a point on the light seen from a reference point, with its solid-angle pdf;
//  - sampleLe: an emitted ray, position pdf in area measure and direction pdf in solid angle;
//  - pdfLe: those two densities for a given emitted direction;
//  - power and lightBounds: for choosing among lights (light_set.h, light_bvh.h).
// A kind may add radiance (Le where a ray hits it), pdfLi (the density of sampleLi's point),
// intensity (point and spot) and infiniteImportance (lights at infinity); Light answers zero for
// a kind without them. Light selection probabilities are the LightSet's business, never a kind's.
#pragma once

#include "core/lights/light_bounds.h"
#include "core/math/ray.h"
#include "core/math/types.h"

#include <concepts>

namespace pathlab {

// In the order of Light's variant of kinds (light.h): the type is the variant's index.
enum class LightType { Area, Point, Spot, Directional, Environment };

struct LightLiSample {
  Spectrum Li{0.f};      // radiance (area) or intensity / d^2 (point, spot) or irradiance (directional)
  Vec3 wi{0.f};          // from the reference point toward the light
  Vec3 pLight{0.f};      // the point on the light (far along wi for directional and environment)
  Vec3 nLight{0.f};      // light surface normal (area); zero for punctual lights
  Vec3 pError{0.f};      // error bound of pLight (area lights, interpolationError)
  Vec2 uv{0.f};          // texture coordinates of pLight (area lights)
  float dist = 0.f;      // distance to pLight (infinity for directional and environment)
  float pdfW = 0.f;      // solid angle at the reference point; 1 for delta lights
  bool isDelta = false;  // delta in position or direction: cannot be hit by a ray
};

struct LightLeSample {
  Spectrum Le{0.f};      // emitted radiance (area) / intensity (point, spot) / irradiance (dir.)
  Ray ray;               // origin on the light, unit direction of travel
  Vec3 pError{0.f};      // error bound of ray.o (area lights, interpolationError)
  Vec2 uv{0.f};          // texture coordinates of ray.o (area lights): where radiance() is read
  Vec3 n{0.f};           // light surface normal (area); for directional and environment, ray.d
  float pdfPosA = 0.f;   // area measure (1 for a point position)
  float pdfDirW = 0.f;   // solid angle (1 for a delta direction)
};

struct EmissionPdf {
  float pdfPosA = 0.f;
  float pdfDirW = 0.f;
};

struct SceneBounds {
  Vec3 center{0.f};
  float radius = 1.f;
};

// The interface of a kind of emitter. pdfLe takes the emitted direction only: every kind's
// densities follow from it (an area light's from its own normal, never a caller's shading normal).
template <class K>
concept Emitter = requires(const K& k, const Vec3& v, Vec2 u) {
  { K::kType } -> std::convertible_to<LightType>;
  { k.sampleLi(v, u) } -> std::same_as<LightLiSample>;
  { k.sampleLe(u, u) } -> std::same_as<LightLeSample>;
  { k.pdfLe(v) } -> std::same_as<EmissionPdf>;
  { k.power() } -> std::same_as<Spectrum>;
  { k.lightBounds() } -> std::same_as<LightBounds>;
};

}  // namespace pathlab
