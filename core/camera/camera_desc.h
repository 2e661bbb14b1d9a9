// Where a camera is and what it sees, as a scene file describes it (glTF cameras, or a framing
// of the scene's bounds): plain data, read by Camera.
#pragma once

#include "core/math/types.h"

#include <optional>
#include <string>

namespace pathlab {

// glTF perspective or orthographic camera, camera-to-world with the camera looking down its -z, +y up.
struct CameraDesc {
  Mat4 cameraToWorld{1.f};
  float yfov = 0.6911f;           // radians (perspective)
  std::optional<float> aspectRatio;
  // glTF's orthographic camera: half the film's width and height (xmag, ymag) in world units;
  // rays are parallel to the view axis and yfov is unused.
  std::optional<Vec2> orthographic;
  std::string name;
  bool operator==(const CameraDesc&) const = default;
};

}  // namespace pathlab
