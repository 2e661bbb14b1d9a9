// A light of any kind: area (one emissive triangle, area_light.h), point or spot (point_light.h),
// directional (directional_light.h) or the environment (environment_emitter.h), held by value in
// a std::variant and dispatched with std::visit. Measured against the switch it replaced and
// against virtual calls (docs/benchmarks.md, session 14): all three equal in time, so the variant,
// which keeps a light a value (no allocation per light, copied with the LightSet) and its type the
// variant's index. What each call means is in emitter.h.
#pragma once

#include "core/lights/area_light.h"
#include "core/lights/directional_light.h"
#include "core/lights/emitter.h"
#include "core/lights/environment_emitter.h"
#include "core/lights/point_light.h"

#include <variant>

namespace pathlab {

class Light {
 public:
  // In LightType's order: type() is the index.
  using Kind = std::variant<AreaLight, PointLight, SpotLight, DirectionalLight, EnvironmentEmitter>;

  template <Emitter K>
  Light(K kind) : kind_(std::move(kind)) {}  // NOLINT(google-explicit-constructor): a kind is a light

  static Light area(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& uv0, const Vec2& uv1,
                    const Vec2& uv2, const Spectrum& emission, const Texture* emissiveTexture, bool twoSided) {
    return AreaLight(p0, p1, p2, uv0, uv1, uv2, emission, emissiveTexture, twoSided);
  }
  static Light point(const Vec3& position, const Spectrum& intensity) { return PointLight(position, intensity); }
  static Light spot(const Vec3& position, const Vec3& direction, const Spectrum& intensity, float innerConeAngle,
                    float outerConeAngle) {
    return SpotLight(position, direction, intensity, innerConeAngle, outerConeAngle);
  }
  static Light directional(const Vec3& direction, const Spectrum& irradiance, const SceneBounds& bounds) {
    return DirectionalLight(direction, irradiance, bounds);
  }
  // `environment` must outlive the light (Scene owns both).
  static Light environment(const EnvironmentLight* environment) { return EnvironmentEmitter(environment); }

  LightType type() const { return static_cast<LightType>(kind_.index()); }
  bool isDeltaPosition() const { return type() == LightType::Point || type() == LightType::Spot; }
  bool isDeltaDirection() const { return type() == LightType::Directional; }
  bool isDelta() const { return type() != LightType::Area && type() != LightType::Environment; }
  bool isInfinite() const { return type() == LightType::Directional || type() == LightType::Environment; }
  const EnvironmentLight* environmentLight() const {
    const EnvironmentEmitter* e = std::get_if<EnvironmentEmitter>(&kind_);
    return e ? e->environment() : nullptr;
  }
  // The kind itself, for code that works on one kind at a time.
  template <class F>
  decltype(auto) visit(F&& f) const { return std::visit(std::forward<F>(f), kind_); }

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const {
    return visit([&](const auto& k) { return k.sampleLi(ref, u); });
  }
  // Solid-angle density at `ref` of sampleLi choosing pLight on this area light (0 for the other
  // kinds). The triangle's own normal decides, not nLight: the caller's may be a shading normal.
  float pdfLi(const Vec3& ref, const Vec3& pLight, const Vec3& nLight) const {
    (void)nLight;
    const AreaLight* a = std::get_if<AreaLight>(&kind_);
    return a ? a->pdfLi(ref, pLight) : 0.f;
  }

  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const {
    return visit([&](const auto& k) { return k.sampleLe(uPos, uDir); });
  }
  // For an area light `p` is on the light and `dir` leaves it; for a point or spot light `p` is
  // ignored; for a directional or environment light `p` is any point on the emitted ray. Each
  // kind's densities follow from `dir` alone (the triangle's own normal decides, not `n`).
  EmissionPdf pdfLe(const Vec3& p, const Vec3& n, const Vec3& dir) const {
    (void)p;
    (void)n;
    return visit([&](const auto& k) { return k.pdfLe(dir); });
  }

  // Radiance leaving an area light at surface point (with uv) in direction `w` (away from the
  // light); zero on the back of a one-sided emitter, and for the other kinds. The triangle's
  // winding decides the front, never a caller's shading normal `n`.
  Spectrum radiance(const Vec3& n, Vec2 uv, const Vec3& w) const {
    (void)n;
    const AreaLight* a = std::get_if<AreaLight>(&kind_);
    return a ? a->radiance(uv, w) : Spectrum(0.f);
  }
  // Emission along `w` for point / spot (intensity), zero for the other kinds.
  Spectrum intensity(const Vec3& w) const {
    return visit([&](const auto& k) {
      if constexpr (requires { k.intensity(w); }) return k.intensity(w);
      else return Spectrum(0.f);
    });
  }

  // Total emitted flux, for selection proportional to power (the kinds say in which units).
  Spectrum power() const {
    return visit([](const auto& k) { return k.power(); });
  }
  // For a light BVH (light_bvh.h): the bounds of a light with a position (area, point, spot), a
  // zero phi for one at infinity or without power.
  LightBounds lightBounds() const;
  // A light at infinity's weight against a BVH's importance, in its units (pi x irradiance),
  // power / bounding disk x pi; zero for the other kinds.
  float infiniteImportance() const {
    return visit([](const auto& k) {
      if constexpr (requires { k.infiniteImportance(); }) return k.infiniteImportance();
      else return 0.f;
    });
  }
  float area() const {
    const AreaLight* a = std::get_if<AreaLight>(&kind_);
    return a ? a->area() : 0.f;
  }

 private:
  Kind kind_;
};

}  // namespace pathlab
