// An RGB float image in memory: what image files are read into and written from.
#pragma once

#include "core/math/types.h"

#include <vector>

namespace pathlab {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, top row first, 3 floats a pixel
  Vec3 at(int x, int y) const {
    const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x));
    return {rgb[i], rgb[i + 1], rgb[i + 2]};
  }
};

}  // namespace pathlab
