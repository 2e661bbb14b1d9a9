// An image texture in linear RGBA float, with glTF sampler wrap modes and bilinear filtering.
#pragma once

#include "core/math/types.h"

#include <string>
#include <vector>

namespace pathlab {

enum class WrapMode { Repeat, ClampToEdge, MirroredRepeat };

struct Texture {
  std::string name;
  int width = 0, height = 0;
  std::vector<Vec4> texels;  // row-major, row 0 at the top (glTF: uv (0,0) is the top-left)
  WrapMode wrapS = WrapMode::Repeat, wrapT = WrapMode::Repeat;
  bool nearest = false;      // glTF magFilter NEAREST

  Vec4 sample(Vec2 uv) const;
  Vec4 average() const;
};

// sRGB transfer function decode (IEC 61966-2-1), for colour textures the glTF spec marks sRGB.
float srgbToLinear(float v);
float linearToSrgb(float v);

}  // namespace pathlab
