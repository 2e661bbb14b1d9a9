// Evaluation of a loaded glTF material at a surface point: factors times texture lookups
// (Khronos glTF 2.0 spec, sec. 3.9.2 and appendix B; texels are already linear, see
// gltf_materials.cpp).
#include "core/scene/material.h"

#include <algorithm>

namespace pathlab {
namespace {

// A reference to a texture that does not exist reads as white, the neutral factor, so a
// hand-built Material with a stale index cannot read out of bounds.
Vec4 lookup(const TextureRef& ref, Vec2 uv, const std::vector<Texture>& textures) {
  if (!ref.valid() || size_t(ref.texture) >= textures.size()) return Vec4(1.f);
  return textures[size_t(ref.texture)].sample(uv);
}

}  // namespace

MaterialPoint evalMaterial(const Material& m, const ShadingInputs& at,
                           const std::vector<Texture>& textures) {
  MaterialPoint p;
  const Vec4 base = m.baseColorFactor * lookup(m.baseColorTexture, at.uv(m.baseColorTexture), textures);
  // glTF 2.0 sec. 3.7.2.1: COLOR_0 "acts as an additional linear multiplier to base color".
  p.baseColor = glm::clamp(Spectrum(base) * at.color, Spectrum(0.f), Spectrum(1.f));
  // glTF 2.0 sec. 3.9.2: roughness in the green channel, metalness in the blue channel.
  const Vec4 mr = lookup(m.metallicRoughnessTexture, at.uv(m.metallicRoughnessTexture), textures);
  p.metallic = std::clamp(m.metallicFactor * mr.b, 0.f, 1.f);
  p.roughness = std::clamp(m.roughnessFactor * mr.g, 0.f, 1.f);
  p.ior = m.ior;
  p.specularFactor = m.specularFactor;
  p.specularColor = m.specularColorFactor;
  p.transmission = std::clamp(m.transmissionFactor, 0.f, 1.f);
  return p;
}

float evalAlpha(const Material& m, Vec2 uv0, Vec2 uv1, float vertexAlpha,
                const std::vector<Texture>& textures) {
  const Vec2 uv = m.baseColorTexture.texCoord == 1 ? uv1 : uv0;
  return m.baseColorFactor.a * lookup(m.baseColorTexture, uv, textures).a * vertexAlpha;
}

Spectrum evalEmission(const Material& m, Vec2 uv, const std::vector<Texture>& textures) {
  if (!m.isEmissive()) return Spectrum(0.f);
  Spectrum e = m.emissiveFactor * m.emissiveStrength;
  if (m.emissiveTexture.valid()) e *= Spectrum(lookup(m.emissiveTexture, uv, textures));
  return e;
}

}  // namespace pathlab
