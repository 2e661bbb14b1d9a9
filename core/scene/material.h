// A glTF 2.0 metallic-roughness material as loaded (factors and texture references), and its
// evaluation at a surface point into the BSDF's parameters and the emitted radiance.
#pragma once

#include "core/bsdf/bsdf.h"
#include "core/texture/texture.h"

#include <string>
#include <vector>

namespace pathlab {

// Index into Scene textures; -1 = none. Only TEXCOORD_0 is supported (the loader warns otherwise).
struct TextureRef {
  int texture = -1;
  bool valid() const { return texture >= 0; }
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
  bool doubleSided = false;

  bool isEmissive() const {
    return emissiveStrength > 0.f && maxComponent(emissiveFactor) > 0.f;
  }
};

MaterialPoint evalMaterial(const Material& m, Vec2 uv, const std::vector<Texture>& textures);
// Emitted radiance (emissiveFactor x emissiveTexture x emissiveStrength), ignoring orientation.
Spectrum evalEmission(const Material& m, Vec2 uv, const std::vector<Texture>& textures);

}  // namespace pathlab
