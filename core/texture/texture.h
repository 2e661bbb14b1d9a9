// An image texture with glTF sampler wrap modes, bilinear filtering and a KHR_texture_transform;
// 8-bit images stay 8-bit (decoded on lookup), 16-bit images and hand-built textures are held as
// linear RGBA floats.
#pragma once

#include "core/math/types.h"
#include "core/texture/uv_transform.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace pathlab {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  std::string name;
  int width = 0, height = 0;
  // Texels are row-major, row 0 at the top (glTF: uv (0,0) is the top-left), held one of two ways:
  //  - `bytes` (when not null): 8-bit, as the file stores them, `channels` bytes a texel (grey,
  //    grey + alpha, RGB, RGBA), shared by every Texture sampling the same image (another sampler
  //    or colour space); decoded on lookup, the colour channels through the sRGB transfer
  //    function when `srgb`, alpha and data textures linearly;
  //  - `texels`: linear RGBA floats (16-bit images, textures built in code).
  std::shared_ptr<const std::vector<uint8_t>> bytes;
  int channels = 4;
  bool srgb = false;
  std::vector<Vec4> texels;
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
  bool nearest = false;      // glTF magFilter NEAREST
  // Applied to every uv before the lookup (KHR_texture_transform). Part of the texture, not of
  // the material: every reader of the texture (the BSDF, the area light's emission and its
  // integral over a triangle) then sees the same transformed image.
  UvTransform transform;

  // The storage holds width x height texels (a texture that does not reads as black).
  bool valid() const;
  // Texel (x, y) as linear RGBA (grey expanded to RGB, missing alpha 1), the wrap modes applied
  // to an index outside the image. Needs valid().
  Vec4 fetch(int64_t x, int64_t y) const;
  // The filtered image at `uv` seen through `transform`.
  Vec4 sample(Vec2 uv) const { return sampleImage(transform.apply(uv)); }
  // The filtered image at image coordinates `st` (after the transform).
  Vec4 sampleImage(Vec2 st) const;
  Vec4 average() const;
  // The bytes holding the texels (shared 8-bit storage counted in full).
  size_t texelBytes() const;
};

// sRGB transfer function decode (IEC 61966-2-1), for colour textures the glTF spec marks sRGB.
float srgbToLinear(float v);
float linearToSrgb(float v);

}  // namespace pathlab
