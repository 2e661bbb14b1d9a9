// glTF materials (metallic-roughness with KHR_materials_emissive_strength, _ior, _specular and
// _transmission) and their images, decoded once into linear float textures.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>

namespace pathlab::gltf {
namespace {

constexpr int kWrapRepeat = 10497, kWrapClamp = 33071, kWrapMirrored = 33648;
constexpr int kFilterNearest = 9728;

// The object of extension `name` in `extensions`, or null.
const tinygltf::Value* findExtension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it != extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

class MaterialReader {
 public:
  MaterialReader(const tinygltf::Model& model, SceneDesc& desc, Warnings& warnings)
      : model_(model), desc_(desc), warnings_(warnings) {}

  Material convert(int index);

 private:
  float finite(double v, const std::string& what) const {
    return toFiniteFloat(v, label_ + ": " + what);
  }
  float number(const tinygltf::Value& object, const char* key, float fallback) const {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsNumber()) throw LoadError(label_ + ": " + key + " is not a number");
    return finite(v.GetNumberAsDouble(), key);
  }
  Vec3 vec3(const std::vector<double>& values, const char* what, Vec3 fallback) const {
    if (values.empty()) return fallback;
    if (values.size() != 3) throw LoadError(label_ + ": " + what + " must have 3 components");
    return {finite(values[0], what), finite(values[1], what), finite(values[2], what)};
  }
  Vec3 vec3(const tinygltf::Value& object, const char* key, Vec3 fallback) const {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    std::vector<double> values;
    for (size_t i = 0; v.IsArray() && i < v.ArrayLen(); ++i) {
      if (!v.Get(int(i)).IsNumber())
        throw LoadError(label_ + ": " + key + " is not a number array");
      values.push_back(v.Get(int(i)).GetNumberAsDouble());
    }
    if (!v.IsArray() || values.empty())
      throw LoadError(label_ + ": " + key + " is not a number array");
    return vec3(values, key, fallback);
  }
  TextureRef texture(int textureIndex, int texCoord, const char* slot, bool srgb);
  TextureRef textureInfo(const tinygltf::TextureInfo& info, const char* slot, bool srgb) {
    return texture(info.index, info.texCoord, slot, srgb);
  }
  int decodedTexture(int imageIndex, int samplerIndex, bool srgb);

  const tinygltf::Model& model_;
  SceneDesc& desc_;
  Warnings& warnings_;
  std::string label_;  // "material 'name'" of the material being converted
  // One Texture per (image, sampler, colour space): an image used both as sRGB colour and as
  // linear data decodes twice.
  std::map<std::tuple<int, int, bool>, int> cache_;
};

WrapMode wrapMode(int mode, Warnings& warnings) {
  switch (mode) {
    case kWrapRepeat: return WrapMode::Repeat;
    case kWrapClamp: return WrapMode::ClampToEdge;
    case kWrapMirrored: return WrapMode::MirroredRepeat;
    default:
      warnings.add("sampler wrap mode " + std::to_string(mode) + " is invalid; REPEAT used");
      return WrapMode::Repeat;
  }
}

// 8-bit sRGB -> linear table: decoding a 4k texture calls the transfer function 50M times
// otherwise.
const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgbToLinear(float(i) / 255.f);
    return t;
  }();
  return table;
}

// tinygltf's stb loader yields row 0 at the top, as Texture and glTF uv (0, 0) expect.
Texture decodeImage(const tinygltf::Image& image, int imageIndex, bool srgb) {
  const std::string name = "image " + std::to_string(imageIndex) + quoted(image.name);
  if (image.image.empty()) {
    if (!image.uri.empty() && !tinygltf::IsDataURI(image.uri)) {
      throw LoadError(name + ": cannot load image file '" + image.uri + "'");
    }
    throw LoadError(name + " has no decodable image data");
  }
  const int w = image.width, h = image.height, comp = image.component, bits = image.bits;
  if (w <= 0 || h <= 0 || comp < 1 || comp > 4 || (bits != 8 && bits != 16)) {
    throw LoadError(name + ": unsupported pixel format (" + std::to_string(comp) + " channels, " +
                    std::to_string(bits) + " bits)");
  }
  const size_t pixels = size_t(w) * size_t(h);
  if (image.image.size() < pixels * size_t(comp) * size_t(bits / 8)) {
    throw LoadError(name + ": pixel data is shorter than " + std::to_string(w) + "x" +
                    std::to_string(h));
  }
  Texture tex;
  tex.name = !image.name.empty() ? image.name : !tinygltf::IsDataURI(image.uri) ? image.uri : name;
  tex.width = w;
  tex.height = h;
  tex.texels.resize(pixels);
  const unsigned char* data = image.image.data();
  const std::array<float, 256>& table = srgbTable();
  for (size_t p = 0; p < pixels; ++p) {
    float c[4];
    for (int k = 0; k < comp; ++k) {
      const size_t i = p * size_t(comp) + size_t(k);
      if (bits == 8) {
        const bool colour = srgb && (comp >= 3 ? k < 3 : k == 0);
        c[k] = colour ? table[data[i]] : float(data[i]) / 255.f;
      } else {
        uint16_t v;
        std::memcpy(&v, data + 2 * i, 2);
        c[k] = float(v) / 65535.f;
        if (srgb && (comp >= 3 ? k < 3 : k == 0)) c[k] = srgbToLinear(c[k]);
      }
    }
    switch (comp) {
      case 1: tex.texels[p] = Vec4(c[0], c[0], c[0], 1.f); break;
      case 2: tex.texels[p] = Vec4(c[0], c[0], c[0], c[1]); break;
      case 3: tex.texels[p] = Vec4(c[0], c[1], c[2], 1.f); break;
      default: tex.texels[p] = Vec4(c[0], c[1], c[2], c[3]); break;
    }
  }
  return tex;
}

int MaterialReader::decodedTexture(int imageIndex, int samplerIndex, bool srgb) {
  auto key = std::make_tuple(imageIndex, samplerIndex, srgb);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  Texture tex = decodeImage(model_.images[size_t(imageIndex)], imageIndex, srgb);
  if (samplerIndex >= 0) {
    const tinygltf::Sampler& s = model_.samplers[size_t(samplerIndex)];
    tex.wrapS = wrapMode(s.wrapS, warnings_);
    tex.wrapT = wrapMode(s.wrapT, warnings_);
    tex.nearest = s.magFilter == kFilterNearest;
  }
  desc_.textures.push_back(std::move(tex));
  const int index = int(desc_.textures.size()) - 1;
  cache_.emplace(key, index);
  return index;
}

TextureRef MaterialReader::texture(int textureIndex, int texCoord, const char* slot, bool srgb) {
  if (textureIndex < 0) return {};
  const std::string what = label_ + ": " + slot;
  if (size_t(textureIndex) >= model_.textures.size()) {
    throw LoadError(what + " refers to texture " + std::to_string(textureIndex) +
                    ", which does not exist");
  }
  const tinygltf::Texture& t = model_.textures[size_t(textureIndex)];
  if (t.source < 0) {
    warnings_.add(what + ": texture " + std::to_string(textureIndex) +
                  " has no image pathlab can decode (only PNG/JPEG sources); ignored");
    return {};
  }
  if (size_t(t.source) >= model_.images.size()) {
    throw LoadError(what + ": texture " + std::to_string(textureIndex) + " refers to image " +
                    std::to_string(t.source) + ", which does not exist");
  }
  if (t.sampler >= 0 && size_t(t.sampler) >= model_.samplers.size()) {
    throw LoadError(what + ": texture " + std::to_string(textureIndex) + " refers to sampler " +
                    std::to_string(t.sampler) + ", which does not exist");
  }
  if (texCoord != 0) {
    warnings_.add(what + " uses TEXCOORD_" + std::to_string(texCoord) +
                  "; only TEXCOORD_0 is supported, TEXCOORD_0 used");
  }
  return TextureRef{decodedTexture(t.source, t.sampler, srgb)};
}

Material MaterialReader::convert(int index) {
  const tinygltf::Material& g = model_.materials[size_t(index)];
  label_ = "material " + std::to_string(index) + quoted(g.name);
  Material m;
  m.name = !g.name.empty() ? g.name : "material " + std::to_string(index);

  const tinygltf::PbrMetallicRoughness& pbr = g.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4)
    throw LoadError(label_ + ": baseColorFactor must have 4 components");
  for (int k = 0; k < 4; ++k) {
    m.baseColorFactor[k] =
        std::clamp(finite(pbr.baseColorFactor[size_t(k)], "baseColorFactor"), 0.f, 1.f);
  }
  m.baseColorTexture = textureInfo(pbr.baseColorTexture, "baseColorTexture", /*srgb=*/true);
  m.metallicFactor = std::clamp(finite(pbr.metallicFactor, "metallicFactor"), 0.f, 1.f);
  m.roughnessFactor = std::clamp(finite(pbr.roughnessFactor, "roughnessFactor"), 0.f, 1.f);
  m.metallicRoughnessTexture =
      textureInfo(pbr.metallicRoughnessTexture, "metallicRoughnessTexture", /*srgb=*/false);
  m.emissiveFactor = glm::max(vec3(g.emissiveFactor, "emissiveFactor", Vec3(0.f)), Vec3(0.f));
  m.emissiveTexture = textureInfo(g.emissiveTexture, "emissiveTexture", /*srgb=*/true);
  m.doubleSided = g.doubleSided;

  if (g.normalTexture.index >= 0) {
    warnings_.add(label_ + ": normalTexture ignored (normal maps are not supported)");
  }
  // occlusionTexture is ignored silently: baked ambient occlusion has no meaning in a path tracer.
  if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
    warnings_.add(label_ + ": alphaMode " + g.alphaMode + " is not supported; rendered OPAQUE");
  }

  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_emissive_strength")) {
    m.emissiveStrength = std::max(number(*e, "emissiveStrength", 1.f), 0.f);
  }
  // The renderer's emitted radiance is this product, in float (the texture only scales it down).
  const Spectrum emission = m.emissiveFactor * m.emissiveStrength;
  if (!isFinite(emission)) {
    throw LoadError(label_ + ": emissiveFactor x emissiveStrength (" +
                    formatNumber(maxComponent(m.emissiveFactor)) + " x " +
                    formatNumber(m.emissiveStrength) + ") " + overflowText());
  }
  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_ior")) {
    const float ior = number(*e, "ior", 1.5f);
    if (ior >= 1.f) {
      m.ior = ior;
    } else {
      warnings_.add(label_ + ": KHR_materials_ior ior " + formatNumber(ior) +
                    " is not supported (needs ior >= 1); 1.5 used");
    }
  }
  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_specular")) {
    m.specularFactor = std::clamp(number(*e, "specularFactor", 1.f), 0.f, 1.f);
    m.specularColorFactor = glm::max(vec3(*e, "specularColorFactor", Vec3(1.f)), Vec3(0.f));
    if (e->Has("specularTexture") || e->Has("specularColorTexture")) {
      warnings_.add(label_ + ": KHR_materials_specular textures are not supported; factors used");
    }
  }
  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_transmission")) {
    m.transmissionFactor = std::clamp(number(*e, "transmissionFactor", 0.f), 0.f, 1.f);
    if (e->Has("transmissionTexture")) {
      warnings_.add(label_ + ": KHR_materials_transmission texture is not supported; factor used");
    }
  }
  return m;
}

}  // namespace

void convertMaterials(const tinygltf::Model& model, SceneDesc& desc, Warnings& warnings) {
  MaterialReader reader(model, desc, warnings);
  desc.materials.reserve(model.materials.size() + 1);  // + the default material, if needed
  for (size_t i = 0; i < model.materials.size(); ++i) {
    desc.materials.push_back(reader.convert(int(i)));
  }
}

}  // namespace pathlab::gltf
