// What an environment light is made of, as the command line or the loader describes it: an
// equirectangular map (or a constant radiance), a strength and a rotation about the vertical.
#pragma once

#include "core/math/types.h"

#include <string>
#include <vector>

namespace pathlab {

struct EnvironmentDesc {
  std::string source;          // the file, or the R,G,B text, for messages
  int width = 0, height = 0;   // 0 x 0: a constant environment
  std::vector<Spectrum> texels;  // width x height, row-major, top row (straight up) first
  Spectrum constant{1.f};      // radiance of a constant environment
  float strength = 1.f;        // scales the radiance
  float rotationDegrees = 0.f;  // right-handed about +y: 90 turns the map's centre from -z to -x

  bool isConstant() const { return width == 0 || height == 0; }
};

}  // namespace pathlab
