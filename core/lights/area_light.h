// An area light: one emissive triangle, Lambertian, one- or two-sided, its emission optionally
// scaled by a texture (glTF emissiveTexture). Sampled uniformly in area, emitting cosine-weighted.
#pragma once

#include "core/lights/emitter.h"
#include "core/math/frame.h"
#include "core/texture/texture.h"

namespace pathlab {

class AreaLight {
 public:
  static constexpr LightType kType = LightType::Area;

  // `emissiveTexture` (may be null) must outlive the light (Scene owns both).
  AreaLight(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec2& uv0, const Vec2& uv1, const Vec2& uv2,
            const Spectrum& emission, const Texture* emissiveTexture, bool twoSided);

  LightLiSample sampleLi(const Vec3& ref, Vec2 u) const;
  // Solid-angle density at `ref` of sampleLi choosing pLight (on the light).
  float pdfLi(const Vec3& ref, const Vec3& pLight) const;
  LightLeSample sampleLe(Vec2 uPos, Vec2 uDir) const;
  EmissionPdf pdfLe(const Vec3& dir) const;
  // Le at the point with texture coordinates uv toward `w` (away from the light); zero on the back
  // of a one-sided emitter. The triangle's winding decides the front, never a caller's normal.
  Spectrum radiance(Vec2 uv, const Vec3& w) const;
  // pi x area x its mean radiance over the triangle (texture integrated once, at construction), per side.
  Spectrum power() const;
  LightBounds lightBounds() const;
  float area() const { return area_; }

 private:
  struct TrianglePoint {
    Vec3 p, pError;
    Vec2 uv;
  };
  // A point uniform in area (sampleLi and sampleLe share it), with its uv and error bound.
  TrianglePoint samplePoint(Vec2 u) const;

  Spectrum emission_{0.f};
  Spectrum meanLe_{0.f};  // emission_ x the texture's mean over the triangle's uvs
  Vec3 p_[3]{};
  Vec2 uv_[3]{};
  Vec3 n_{0.f};  // geometric normal (winding order)
  Frame frame_;
  float area_ = 0.f;
  bool twoSided_ = false;
  const Texture* texture_ = nullptr;
};

}  // namespace pathlab
