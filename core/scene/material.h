// A glTF 2.0 metallic-roughness material as loaded (factors and texture references), and its
// evaluation at a surface point into the BSDF's parameters and the emitted radiance.
#pragma once

#include "core/bsdf/bsdf.h"
#include "core/media/medium.h"
#include "core/texture/texture.h"

#include <optional>
#include <string>
#include <vector>

namespace pathlab {

// Index into Scene textures (-1 = none) and the vertex texture coordinate set it reads
// (TEXCOORD_0 or TEXCOORD_1); the texture itself carries its KHR_texture_transform.
struct TextureRef {
  int texture = -1;
  int texCoord = 0;
  bool valid() const { return texture >= 0; }
};

// glTF 2.0 sec. 3.9.4 (alpha coverage): OPAQUE ignores alpha; MASK cuts the surface out where
// alpha < alphaCutoff; BLEND is rendered as stochastic transparency: a ray meets the surface with
// probability alpha and passes through it otherwise (scene.cpp), which on average is the
// "over" blend a rasteriser draws, for every technique, shadow rays and connections included.
enum class AlphaMode { Opaque, Mask, Blend };

// The vertex attributes a material reads at a surface point, interpolated over the triangle.
struct ShadingInputs {
  Vec2 uv0{0.f};
  Vec2 uv1{0.f};
  Spectrum color{1.f};  // COLOR_0 (rgb; its alpha acts only through the alpha modes)
  Vec2 uv(const TextureRef& ref) const { return ref.texCoord == 1 ? uv1 : uv0; }
};

struct Material {
  std::string name;
  Vec4 baseColorFactor{1.f};
  TextureRef baseColorTexture;         // sRGB
  float metallicFactor = 1.f;
  float roughnessFactor = 1.f;
  TextureRef metallicRoughnessTexture; // linear: G = roughness, B = metallic
  Spectrum emissiveFactor{0.f};
  float emissiveStrength = 1.f;        // KHR_materials_emissive_strength
  TextureRef emissiveTexture;          // sRGB
  float ior = 1.5f;                    // KHR_materials_ior
  float specularFactor = 1.f;          // KHR_materials_specular
  Spectrum specularColorFactor{1.f};
  float transmissionFactor = 0.f;      // KHR_materials_transmission
  // KHR_materials_volume with thicknessFactor > 0 (and _volume_scatter): with transmission, the
  // closed mesh bounds a homogeneous medium (core/media). Thickness 0 is glTF's thin-walled case.
  std::optional<VolumeDesc> volume;
  bool doubleSided = false;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  TextureRef normalTexture;            // linear, tangent space (glTF 2.0 sec. 3.9.3)
  float normalScale = 1.f;

  // Whether rays must ask the material whether they meet the surface (alpha < 1 somewhere).
  bool hasAlphaTest() const { return alphaMode != AlphaMode::Opaque; }

  // An index-matched interface: fully transmissive, ior 1, smooth, not metallic, untextured. Rays
  // pass straight through it; in a scene with media it is never a path vertex (only the medium
  // changes), elsewhere it is the delta glass it describes.
  bool isIndexMatched() const {
    return transmissionFactor >= 1.f && ior == 1.f && roughnessFactor == 0.f && metallicFactor == 0.f &&
           !metallicRoughnessTexture.valid() && !isEmissive() && alphaMode == AlphaMode::Opaque;
  }

  bool isEmissive() const {
    return emissiveStrength > 0.f && maxComponent(emissiveFactor) > 0.f;
  }
};

MaterialPoint evalMaterial(const Material& m, const ShadingInputs& at,
                           const std::vector<Texture>& textures);
// At a point without TEXCOORD_1 or vertex colours (both sets read `uv`).
inline MaterialPoint evalMaterial(const Material& m, Vec2 uv, const std::vector<Texture>& textures) {
  return evalMaterial(m, ShadingInputs{uv, uv, Spectrum(1.f)}, textures);
}
// alpha = baseColorFactor.a x baseColorTexture.a x COLOR_0.a (glTF 2.0 sec. 3.9.4).
float evalAlpha(const Material& m, Vec2 uv0, Vec2 uv1, float vertexAlpha,
                const std::vector<Texture>& textures);
// Emitted radiance (emissiveFactor x emissiveTexture x emissiveStrength), ignoring orientation;
// `uv` in the emissive texture's own set (emissiveTexture.texCoord).
Spectrum evalEmission(const Material& m, Vec2 uv, const std::vector<Texture>& textures);

}  // namespace pathlab
