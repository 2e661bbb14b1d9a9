// Where a camera is and what it sees, as a scene file describes it (glTF cameras, or a framing
// of the scene's bounds): plain data, read by Camera.
#pragma once

#include "core/math/types.h"

#include <optional>
#include <string>

namespace pathlab {

// glTF perspective camera, camera-to-world with the camera looking down its -z, +y up.
struct CameraDesc {
  Mat4 cameraToWorld{1.f};
  float yfov = 0.6911f;           // radians
  std::optional<float> aspectRatio;
  std::string name;
  bool operator==(const CameraDesc&) const = default;
};

}  // namespace pathlab
