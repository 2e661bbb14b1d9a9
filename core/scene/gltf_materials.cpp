// glTF materials (metallic-roughness with KHR_materials_emissive_strength, _ior, _specular and
// _transmission; alpha modes; normal maps; KHR_texture_transform) and their images, each held
// once (8-bit as 8-bit) and shared by its textures.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
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

// An image's pixels as tinygltf decoded them, moved out of the model once and shared by every
// Texture made from it.
struct ImagePixels {
  std::string name;  // for messages and Texture::name
  int width = 0, height = 0, channels = 0, bits = 0;
  std::shared_ptr<const std::vector<uint8_t>> data;
};

class MaterialReader {
 public:
  MaterialReader(tinygltf::Model& model, SceneDesc& desc, Warnings& warnings)
      : model_(model), desc_(desc), warnings_(warnings) {}

  Material convert(int index);

 private:
  // KHR_materials_volume and the KHR_materials_volume_scatter draft (glTF PR 2453): the medium a
  // closed transmissive mesh bounds. thicknessFactor 0 is glTF's thin-walled surface (no medium);
  // any other thickness is only a rasteriser's estimate, so pathlab uses the geometry instead and
  // ignores thicknessTexture.
  void readVolume(const tinygltf::Material& g, Material& m) {
    const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_volume");
    const tinygltf::Value* scatter = findExtension(g.extensions, "KHR_materials_volume_scatter");
    if (!e) {
      if (scatter) warnings_.add(label_, "KHR_materials_volume_scatter without KHR_materials_volume is ignored");
      return;
    }
    if (!(number(*e, "thicknessFactor", 0.f) > 0.f)) return;
    VolumeDesc v;
    v.attenuationColor = glm::clamp(vec3(*e, "attenuationColor", Vec3(1.f)), Vec3(0.f), Vec3(1.f));
    v.attenuationDistance = number(*e, "attenuationDistance", std::numeric_limits<float>::infinity());
    if (!(v.attenuationDistance > 0.f)) {
      warnings_.add(label_, "KHR_materials_volume attenuationDistance " + formatNumber(v.attenuationDistance) +
                    " is not positive; no attenuation used");
      v.attenuationDistance = std::numeric_limits<float>::infinity();
    }
    if (scatter) {
      v.scatters = true;
      v.multiscatterColor = glm::clamp(vec3(*scatter, "multiscatterColor", Vec3(0.f)), Vec3(0.f), Vec3(1.f));
      v.anisotropy = std::clamp(number(*scatter, "scatterAnisotropy", 0.f), -1.f, 1.f);
      if (scatter->Has("multiscatterColorTexture"))
        warnings_.add(label_, "KHR_materials_volume_scatter texture is not supported; factor used");
    }
    if (m.transmissionFactor <= 0.f)
      warnings_.add(label_, "KHR_materials_volume without transmission bounds no medium (the surface is opaque)");
    v.grid = readVolumeGrid(g);
    m.volume = v;
  }

  // PATHLAB_materials_volume_grid (README, "Heterogeneous media"): {"uri", "grid", "densityScale"}.
  // The grid itself is read once the nodes have placed it (gltf_loader.cpp, loadVolumeGrids).
  std::optional<VolumeGridRef> readVolumeGrid(const tinygltf::Material& g) {
    const tinygltf::Value* e = findExtension(g.extensions, "PATHLAB_materials_volume_grid");
    if (!e) return std::nullopt;
    const std::string what = label_ + ": PATHLAB_materials_volume_grid";
    auto text = [&](const char* key, const char* fallback) {
      if (!e->Has(key)) {
        if (fallback) return std::string(fallback);
        throw LoadError(what + " has no " + key);
      }
      const tinygltf::Value& v = e->Get(key);
      if (!v.IsString() || v.Get<std::string>().empty()) throw LoadError(what + ": " + key + " is not a non-empty string");
      return v.Get<std::string>();
    };
    VolumeGridRef ref;
    ref.uri = text("uri", nullptr);
    if (ref.uri.rfind("data:", 0) == 0) throw LoadError(what + ": uri must name a .vdb file, not a data URI");
    ref.grid = text("grid", "density");
    ref.densityScale = number(*e, "densityScale", 1.f);
    if (!(ref.densityScale >= 0.f && ref.densityScale <= 1e6f))
      throw LoadError(what + ": densityScale " + formatNumber(ref.densityScale) + " is outside [0, 1e6]");
    return ref;
  }

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
  Vec2 vec2(const tinygltf::Value& object, const char* key, Vec2 fallback) const {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsArray() || v.ArrayLen() != 2 || !v.Get(0).IsNumber() || !v.Get(1).IsNumber())
      throw LoadError(label_ + ": " + key + " is not an array of 2 numbers");
    return {finite(v.Get(0).GetNumberAsDouble(), key), finite(v.Get(1).GetNumberAsDouble(), key)};
  }
  TextureRef texture(int textureIndex, int texCoord, const tinygltf::ExtensionMap& extensions,
                     const char* slot, bool srgb);
  template <class Info>
  TextureRef textureInfo(const Info& info, const char* slot, bool srgb) {
    return texture(info.index, info.texCoord, info.extensions, slot, srgb);
  }
  int decodedTexture(int imageIndex, int samplerIndex, bool srgb, const UvTransform& transform);
  const ImagePixels& pixels(int imageIndex);

  tinygltf::Model& model_;  // its images' pixels are moved out as they are first used
  SceneDesc& desc_;
  Warnings& warnings_;
  std::string label_;  // "material 'name'" of the material being converted
  // One Texture per (image, sampler, colour space, uv transform), all of an image's Textures
  // sharing its pixels: each image is decoded once (by tinygltf) and held once.
  std::map<std::tuple<int, int, bool, std::array<float, 6>>, int> cache_;
  std::map<int, ImagePixels> pixels_;
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

// tinygltf's stb loader yields row 0 at the top, as Texture and glTF uv (0, 0) expect, with the
// file's own channels (loadImageChecked asks it to preserve them).
ImagePixels takePixels(tinygltf::Image& image, int imageIndex) {
  const std::string name = "image " + std::to_string(imageIndex) + quotedName(image.name);
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
  ImagePixels p;
  p.name = !image.name.empty() ? image.name : !tinygltf::IsDataURI(image.uri) ? image.uri : name;
  p.width = w;
  p.height = h;
  p.channels = comp;
  p.bits = bits;
  p.data = std::make_shared<const std::vector<uint8_t>>(std::move(image.image));
  image.image.clear();
  return p;
}

// A Texture over `pixels` in colour space `srgb`: 8-bit pixels are shared as they are (decoded on
// lookup); 16-bit ones are decoded here into linear floats.
Texture makeTexture(const ImagePixels& pixels, bool srgb) {
  Texture tex;
  tex.name = pixels.name;
  tex.width = pixels.width;
  tex.height = pixels.height;
  tex.channels = pixels.channels;
  tex.srgb = srgb;
  if (pixels.bits == 8) {
    tex.bytes = pixels.data;
    return tex;
  }
  const int comp = pixels.channels;
  const size_t count = size_t(pixels.width) * size_t(pixels.height);
  tex.texels.resize(count);
  const unsigned char* data = pixels.data->data();
  for (size_t p = 0; p < count; ++p) {
    float c[4];
    for (int k = 0; k < comp; ++k) {
      const size_t i = p * size_t(comp) + size_t(k);
      uint16_t v;
      std::memcpy(&v, data + 2 * i, 2);
      c[k] = float(v) / 65535.f;
      if (srgb && (comp >= 3 ? k < 3 : k == 0)) c[k] = srgbToLinear(c[k]);
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

const ImagePixels& MaterialReader::pixels(int imageIndex) {
  auto it = pixels_.find(imageIndex);
  if (it == pixels_.end()) {
    it = pixels_.emplace(imageIndex, takePixels(model_.images[size_t(imageIndex)], imageIndex)).first;
  }
  return it->second;
}

int MaterialReader::decodedTexture(int imageIndex, int samplerIndex, bool srgb,
                                   const UvTransform& transform) {
  const std::array<float, 6> matrix = {transform.a.x, transform.a.y, transform.b.x,
                                       transform.b.y, transform.c.x, transform.c.y};
  auto key = std::make_tuple(imageIndex, samplerIndex, srgb, matrix);
  if (auto it = cache_.find(key); it != cache_.end()) return it->second;
  Texture tex = makeTexture(pixels(imageIndex), srgb);
  tex.transform = transform;
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

TextureRef MaterialReader::texture(int textureIndex, int texCoord,
                                   const tinygltf::ExtensionMap& extensions, const char* slot,
                                   bool srgb) {
  if (textureIndex < 0) return {};
  const std::string what = label_ + ": " + slot;
  // KHR_texture_transform on the textureInfo: offset, rotation, scale, and a texCoord that
  // overrides the textureInfo's own.
  UvTransform transform;
  if (const tinygltf::Value* e = findExtension(extensions, "KHR_texture_transform")) {
    const std::string saved = label_;
    label_ = what + " KHR_texture_transform";
    transform = UvTransform::fromGltf(vec2(*e, "offset", Vec2(0.f)), number(*e, "rotation", 0.f),
                                      vec2(*e, "scale", Vec2(1.f)));
    if (e->Has("texCoord")) texCoord = int(number(*e, "texCoord", float(texCoord)));
    label_ = saved;
  }
  if (size_t(textureIndex) >= model_.textures.size()) {
    throw LoadError(what + " refers to texture " + std::to_string(textureIndex) +
                    ", which does not exist");
  }
  const tinygltf::Texture& t = model_.textures[size_t(textureIndex)];
  if (t.source < 0) {
    warnings_.add(what, "texture " + std::to_string(textureIndex) +
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
  if (texCoord != 0 && texCoord != 1) {
    warnings_.add(what, "TEXCOORD_" + std::to_string(texCoord) +
                           " is not supported (TEXCOORD_0 and TEXCOORD_1 are); TEXCOORD_0 used");
    texCoord = 0;
  }
  return TextureRef{decodedTexture(t.source, t.sampler, srgb, transform), texCoord};
}

Material MaterialReader::convert(int index) {
  const tinygltf::Material& g = model_.materials[size_t(index)];
  label_ = "material " + std::to_string(index) + quotedName(g.name);
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

  m.normalTexture = textureInfo(g.normalTexture, "normalTexture", /*srgb=*/false);
  m.normalScale = finite(g.normalTexture.scale, "normalTexture.scale");
  // occlusionTexture is ignored silently: baked ambient occlusion has no meaning in a path tracer.
  if (g.alphaMode == "MASK") {
    m.alphaMode = AlphaMode::Mask;
    m.alphaCutoff = std::max(finite(g.alphaCutoff, "alphaCutoff"), 0.f);
  } else if (g.alphaMode == "BLEND") {
    m.alphaMode = AlphaMode::Blend;
  } else if (!g.alphaMode.empty() && g.alphaMode != "OPAQUE") {
    warnings_.add(label_, "alphaMode " + g.alphaMode + " is not a glTF alpha mode; OPAQUE used");
  }

  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_emissive_strength")) {
    // The extension's schema has minimum 0: a negative strength is an invalid file, not "no light".
    m.emissiveStrength = number(*e, "emissiveStrength", 1.f);
    if (m.emissiveStrength < 0.f)
      throw LoadError(label_ + ": KHR_materials_emissive_strength emissiveStrength " + formatNumber(m.emissiveStrength) +
                      " is negative (the extension requires >= 0)");
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
      warnings_.add(label_, "KHR_materials_ior ior " + formatNumber(ior) +
                    " is not supported (needs ior >= 1); 1.5 used");
    }
  }
  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_specular")) {
    m.specularFactor = std::clamp(number(*e, "specularFactor", 1.f), 0.f, 1.f);
    m.specularColorFactor = glm::max(vec3(*e, "specularColorFactor", Vec3(1.f)), Vec3(0.f));
    if (e->Has("specularTexture") || e->Has("specularColorTexture")) {
      warnings_.add(label_, "KHR_materials_specular textures are not supported; factors used");
    }
  }
  if (const tinygltf::Value* e = findExtension(g.extensions, "KHR_materials_transmission")) {
    m.transmissionFactor = std::clamp(number(*e, "transmissionFactor", 0.f), 0.f, 1.f);
    if (e->Has("transmissionTexture")) {
      warnings_.add(label_, "KHR_materials_transmission texture is not supported; factor used");
    }
  }
  readVolume(g, m);
  return m;
}

}  // namespace

void convertMaterials(tinygltf::Model& model, SceneDesc& desc, Warnings& warnings) {
  MaterialReader reader(model, desc, warnings);
  desc.materials.reserve(model.materials.size() + 1);  // + the default material, if needed
  for (size_t i = 0; i < model.materials.size(); ++i) {
    desc.materials.push_back(reader.convert(int(i)));
  }
}

}  // namespace pathlab::gltf
