// Emitters: area (one emissive triangle), point, spot and directional (KHR_lights_punctual), and
// the environment (environment_light.h), which this class refers to but does not own.
// Each provides what path tracing and bidirectional path tracing ask of a light:
//  - sampleLi: a point on the light seen from a reference point, with its solid-angle pdf;
//  - sampleLe: an emitted ray, position pdf in area measure and direction pdf in solid angle;
//  - pdfLe: those two densities for a given emitted ray;
//  - radiance: Le when a ray hits an area light.
// Light selection probabilities are the LightSet's business, never included here.
#pragma once

#include "core/lights/environment_light.h"
#include "core/lights/light_bounds.h"
#include "core/math/frame.h"
#include "core/math/types.h"
#include "core/math/ray.h"
#include "core/texture/texture.h"

namespace pathlab {

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

class Light {
 public:
  static Light area(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& uv0,
                    const Vec2& uv1, const Vec2& uv2, const Spectrum& emission,
                    const Texture* emissiveTexture, bool twoSided);
  static Light point(const Vec3& position, const Spectrum& intensity);
  static Light spot(const Vec3& position, const Vec3& direction, const Spectrum& intensity,
                    float innerConeAngle, float outerConeAngle);
  static Light directional(const Vec3& direction, const Spectrum& irradiance,
                           const SceneBounds& bounds);
  // `environment` must outlive the light (Scene owns both).
  static Light environment(const EnvironmentLight* environment);

  LightType type() const { return type_; }
  bool isDeltaPosition() const { return type_ == LightType::Point || type_ == LightType::Spot; }
  bool isDeltaDirection() const { return type_ == LightType::Directional; }
  bool isDelta() const { return type_ != LightType::Area && type_ != LightType::Environment; }
  bool isInfinite() const { return type_ == LightType::Directional || type_ == LightType::Environment; }
  const EnvironmentLight* environmentLight() const { return environment_; }

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  // Solid-angle density at `ref` of sampleLi choosing pLight on this area light (0 for delta).
  float pdfLi(const Vec3& ref, const Vec3& pLight, const Vec3& nLight) const;

  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  // For an area light `p` is on the light and `dir` leaves it; for a point or spot light `p` is
  // ignored; for a directional or environment light `p` is any point on the emitted ray (the
  // position density is the disk's, the direction density the map's at -dir).
  EmissionPdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& dir) const;

  // Radiance leaving an area light at surface point (with uv) in direction `w` (away from the
  // light); zero on the back of a one-sided emitter, and for punctual lights.
  Spectrum radiance(const Vec3& n, Vec2 uv, const Vec3& w) const;
  // Emission along `w` for point / spot (intensity) -- used by sampleLe and connections.
  Spectrum intensity(const Vec3& w) const;

  // Total emitted flux, for selection proportional to power. An area light's is pi x area x its
  // mean radiance over the triangle (texture integrated once, at construction; per side).
  Spectrum power() const;
  // For a light BVH (light_bvh.h): the bounds of a light with a position (area, point, spot), a
  // zero phi for one at infinity or without power.
  LightBounds lightBounds() const;
  // A light at infinity's weight against a BVH's importance, in its units (pi x irradiance): pi E
  // for a directional light, pi x a quarter of the environment's integral of L over the sphere
  // (pi L for a uniform one: what a surface facing up receives). Both are power / bounding disk x pi.
  float infiniteImportance() const;
  float area() const { return area_; }

 private:
  LightType type_ = LightType::Point;
  Spectrum emission_{0.f};  // Le, intensity or irradiance by type
  Spectrum meanLe_{0.f};    // area: emission_ x the texture's mean over the triangle's uvs
  Vec3 p_[3]{};             // triangle vertices; p_[0] is the position of point / spot lights
  Vec2 uv_[3]{};
  Vec3 n_{0.f};             // area: geometric normal; spot / directional: direction of travel
  Frame frame_;
  float area_ = 0.f;
  bool twoSided_ = false;
  const Texture* texture_ = nullptr;
  float cosInner_ = 1.f, cosOuter_ = 0.f;
  SceneBounds bounds_;
  const EnvironmentLight* environment_ = nullptr;
};

}  // namespace pathlab
