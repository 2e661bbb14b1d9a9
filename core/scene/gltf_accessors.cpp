// Bounds-checked reading of glTF accessors (glTF 2.0 spec, sec. 3.6) into float and index arrays.
#include "core/scene/gltf_internal.h"

#include "core/image/image_budget.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

namespace pathlab::gltf {
namespace {

struct AccessorView {
  const unsigned char* data = nullptr;
  size_t count = 0;
  size_t stride = 0;
  int componentType = 0;
  int components = 0;
  bool normalized = false;
};

std::string accessorName(int index, const std::string& what) {
  return "accessor " + std::to_string(index) + " (" + what + ")";
}

// Validates the accessor -> bufferView -> buffer chain and the byte range the accessor reads
// before returning a pointer into the buffer (glTF 2.0 spec, sec. 3.6.2.4, data alignment).
AccessorView viewAccessor(const tinygltf::Model& model, int index, const std::string& what) {
  if (index < 0 || size_t(index) >= model.accessors.size()) {
    throw LoadError(what + " refers to accessor " + std::to_string(index) +
                    ", which does not exist");
  }
  const tinygltf::Accessor& a = model.accessors[size_t(index)];
  const std::string name = accessorName(index, what);
  if (a.sparse.isSparse) {
    throw LoadError(name + " is a sparse accessor; sparse accessors are not supported");
  }
  const int componentSize = tinygltf::GetComponentSizeInBytes(uint32_t(a.componentType));
  const int components = tinygltf::GetNumComponentsInType(uint32_t(a.type));
  if (componentSize <= 0 || components <= 0) {
    throw LoadError(name + " has an invalid componentType or type");
  }
  if (a.bufferView < 0) {
    // Legal glTF (all zeros) but never useful for geometry; refusing it avoids a zero-filled
    // allocation of an arbitrary, unchecked count.
    throw LoadError(name + " has no bufferView");
  }
  if (size_t(a.bufferView) >= model.bufferViews.size()) {
    throw LoadError(name + " refers to bufferView " + std::to_string(a.bufferView) +
                    ", which does not exist");
  }
  const tinygltf::BufferView& bv = model.bufferViews[size_t(a.bufferView)];
  if (bv.buffer < 0 || size_t(bv.buffer) >= model.buffers.size()) {
    throw LoadError("bufferView " + std::to_string(a.bufferView) + " of " + name +
                    " refers to buffer " + std::to_string(bv.buffer) + ", which does not exist");
  }
  const size_t bufferSize = model.buffers[size_t(bv.buffer)].data.size();
  if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset) {
    throw LoadError("bufferView " + std::to_string(a.bufferView) + " of " + name +
                    " reads past the end of buffer " + std::to_string(bv.buffer) + " (bytes " +
                    std::to_string(bv.byteOffset) + "+" + std::to_string(bv.byteLength) +
                    ", buffer has " + std::to_string(bufferSize) + ")");
  }

  AccessorView view;
  view.count = a.count;
  view.componentType = a.componentType;
  view.components = components;
  view.normalized = a.normalized;
  const size_t elementSize = size_t(componentSize) * size_t(components);
  view.stride = bv.byteStride != 0 ? bv.byteStride : elementSize;
  if (bv.byteStride != 0 && bv.byteStride < elementSize) {
    throw LoadError(name + ": byteStride " + std::to_string(bv.byteStride) + " of bufferView " +
                    std::to_string(a.bufferView) + " is smaller than one element (" +
                    std::to_string(elementSize) + " bytes)");
  }
  if (a.count > 0) {
    // Last byte read: byteOffset + (count - 1) * stride + elementSize <= byteLength, rearranged
    // so nothing overflows.
    const bool fits = a.byteOffset <= bv.byteLength &&
                      elementSize <= bv.byteLength - a.byteOffset &&
                      (a.count - 1) <= (bv.byteLength - a.byteOffset - elementSize) / view.stride;
    if (!fits) {
      throw LoadError(name + " reads past the end of bufferView " + std::to_string(a.bufferView) +
                      " of buffer " + std::to_string(bv.buffer) + " (count " +
                      std::to_string(a.count) + ", stride " + std::to_string(view.stride) +
                      ", byteOffset " + std::to_string(a.byteOffset) + ", bufferView byteLength " +
                      std::to_string(bv.byteLength) + ")");
    }
    view.data = model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
  }
  return view;
}

// Normalized integers map to [0, 1] (unsigned) or [-1, 1] (signed: max(c / MAX, -1)), as in
// glTF 2.0 spec sec. 3.11 and KHR_mesh_quantization.
template <class T>
float toFloat(const unsigned char* p, bool normalized) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  if constexpr (std::is_floating_point_v<T>) {
    return float(v);
  } else {
    if (!normalized) return float(v);
    const float scaled = float(double(v) / double(std::numeric_limits<T>::max()));
    return std::is_signed_v<T> ? std::max(scaled, -1.f) : scaled;
  }
}

template <class T>
void readTyped(const AccessorView& view, int take, float* out, const std::string& name) {
  for (size_t i = 0; i < view.count; ++i) {
    const unsigned char* element = view.data + i * view.stride;
    for (int c = 0; c < take; ++c) {
      float& f = out[i * size_t(take) + size_t(c)];
      f = toFloat<T>(element + size_t(c) * sizeof(T), view.normalized);
      if constexpr (std::is_same_v<T, double>) {
        // Only a double can be finite and still not fit; a non-finite value stays for the
        // caller's own check (positions refused, normals and uvs repaired).
        double v;
        std::memcpy(&v, element + size_t(c) * sizeof(T), sizeof(T));
        if (std::isfinite(v) && !std::isfinite(f)) {
          throw LoadError(name + ": element " + std::to_string(i) + " component " +
                          std::to_string(c) + ", " + formatNumber(v) + ", " + overflowText());
        }
      }
    }
  }
}

// Converts `take` components of every element to float, row after row into `out`.
void readFloats(const AccessorView& view, int take, float* out, const std::string& name) {
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: readTyped<float>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: readTyped<uint8_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_BYTE: readTyped<int8_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: readTyped<uint16_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_SHORT: readTyped<int16_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: readTyped<uint32_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_INT: readTyped<int32_t>(view, take, out, name); break;
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: readTyped<double>(view, take, out, name); break;
    default: break;  // rejected by viewAccessor
  }
}

template <class V>
std::vector<V> readVectors(const tinygltf::Model& model, int index, const std::string& what,
                           int components, const char* typeName) {
  const AccessorView view = viewAccessor(model, index, what);
  if (view.components != components) {
    throw LoadError(accessorName(index, what) + " must have type " + typeName);
  }
  static_assert(sizeof(V) == sizeof(float) * V::length());
  std::vector<V> out(view.count);
  if (view.count > 0) readFloats(view, components, &out[0][0], accessorName(index, what));
  return out;
}

}  // namespace

std::vector<Vec3> readVec3(const tinygltf::Model& model, int accessor, const std::string& what) {
  return readVectors<Vec3>(model, accessor, what, 3, "VEC3");
}

std::vector<Vec2> readVec2(const tinygltf::Model& model, int accessor, const std::string& what) {
  return readVectors<Vec2>(model, accessor, what, 2, "VEC2");
}

std::vector<Vec4> readVec4(const tinygltf::Model& model, int accessor, const std::string& what) {
  return readVectors<Vec4>(model, accessor, what, 4, "VEC4");
}

std::vector<Vec4> readColors(const tinygltf::Model& model, int accessor, const std::string& what) {
  const AccessorView view = viewAccessor(model, accessor, what);
  if (view.components == 4) return readVec4(model, accessor, what);
  // glTF 2.0 sec. 3.7.2.1: COLOR_n is VEC3 or VEC4; a VEC3 colour is opaque.
  const std::vector<Vec3> rgb = readVectors<Vec3>(model, accessor, what, 3, "VEC3 or VEC4");
  std::vector<Vec4> out(rgb.size());
  for (size_t i = 0; i < rgb.size(); ++i) out[i] = Vec4(rgb[i], 1.f);
  return out;
}

std::vector<uint32_t> readIndices(const tinygltf::Model& model, int accessor,
                                  const std::string& what) {
  const AccessorView view = viewAccessor(model, accessor, what);
  if (view.components != 1) {
    throw LoadError(accessorName(accessor, what) + " must have type SCALAR");
  }
  std::vector<uint32_t> out(view.count);
  auto read = [&](auto tag) {
    using T = decltype(tag);
    for (size_t i = 0; i < view.count; ++i) {
      T v;
      std::memcpy(&v, view.data + i * view.stride, sizeof(T));
      out[i] = uint32_t(v);
    }
  };
  switch (view.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: read(uint8_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: read(uint16_t{}); break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: read(uint32_t{}); break;
    default:
      throw LoadError(accessorName(accessor, what) +
                      " must have componentType UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT");
  }
  return out;
}

namespace {

// Decoded bytes per byte of a PNG at the most: deflate's limit is 1032:1.
constexpr uint64_t kMaxPngRatio = 1100;

// Why stb_image must not decode these bytes, or "": a Radiance HDR (stb_image 2.27 hangs on a
// truncated one, and glTF has no HDR textures), or a header whose size exceeds kMaxImageTexels or
// what a PNG of `size` bytes can hold. stbi_info reads the header only.
std::string imageClaimProblem(const unsigned char* bytes, int size) {
  if (stbi_is_hdr_from_memory(bytes, size)) return "a Radiance HDR image, not a glTF texture (use PNG or JPEG)";
  int w = 0, h = 0, comp = 0;
  if (!stbi_info_from_memory(bytes, size, &w, &h, &comp)) return "";  // stb_image refuses it itself
  const bool png = size >= 8 && std::memcmp(bytes, "\x89PNG\r\n\x1a\n", 8) == 0;
  const uint64_t texels = w > 0 && h > 0 ? uint64_t(w) * uint64_t(h) : 0;
  const std::string claim = "the header claims " + std::to_string(w) + "x" + std::to_string(h) + " texels";
  if (texels > kMaxImageTexels) return claim + ", more than the " + std::to_string(kMaxImageTexels) + " pathlab reads";
  // A PNG row is a filter byte and at least a bit per texel (1-bit grey or palette).
  if (png && uint64_t(h) * (1 + (uint64_t(w) + 7) / 8) > kMaxPngRatio * uint64_t(size))
    return claim + ", more than " + std::to_string(size) + " bytes of PNG can hold (truncated or corrupt)";
  return "";
}

}  // namespace

bool loadImageChecked(tinygltf::Image* image, int imageIndex, std::string* err, std::string* warn,
                      int reqWidth, int reqHeight, const unsigned char* bytes, int size,
                      void* userData) {
  const auto* model = static_cast<const tinygltf::Model*>(userData);
  if (image->bufferView >= 0 && model != nullptr) {
    // tinygltf has checked that the bufferView and its buffer exist, not the byte range.
    const tinygltf::BufferView& bv = model->bufferViews[size_t(image->bufferView)];
    const size_t bufferSize = model->buffers[size_t(bv.buffer)].data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset ||
        bv.byteLength > size_t(std::numeric_limits<int>::max())) {
      if (err) {
        *err += "image " + std::to_string(imageIndex) + ": bufferView " +
                std::to_string(image->bufferView) + " reads past the end of buffer " +
                std::to_string(bv.buffer) + "\n";
      }
      return false;
    }
  }
  if (bytes == nullptr || size <= 0) {
    if (err) *err += "image " + std::to_string(imageIndex) + " is empty\n";
    return false;
  }
  if (const std::string why = imageClaimProblem(bytes, size); !why.empty()) {
    if (err) *err += "image " + std::to_string(imageIndex) + ": " + why + "\n";
    return false;
  }
  // Decoded to 8 or 16 bits by tinygltf's own stb_image loader, keeping the file's channels: an
  // RGB JPEG stays 3 bytes a texel (Texture expands grey and RGB on lookup).
  // tinygltf 2.7 reads its options through user_data as `struct LoadImageDataOption { bool
  // preserve_channels; }`, declared only in its implementation section: this mirrors it.
  struct PreserveChannelsOption {
    bool preserveChannels = true;
  } option;
  static_assert(sizeof(PreserveChannelsOption) == sizeof(bool));
  return tinygltf::LoadImageData(image, imageIndex, err, warn, reqWidth, reqHeight, bytes, size,
                                 &option);
}

}  // namespace pathlab::gltf
