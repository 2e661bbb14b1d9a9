// glTF 2.0 (.gltf / .glb) -> SceneDesc through tinygltf: the whole node hierarchy of the default
// scene flattened to world-space triangles, metallic-roughness materials with the supported
// KHR_materials_* extensions, KHR_lights_punctual lights and the first perspective camera.
#pragma once

#include "core/scene/scene_desc.h"

#include <stdexcept>
#include <string>

namespace pathlab {

// Thrown for any input pathlab cannot render correctly. what() is one line that names the file
// and the problem, e.g. "scenes/box.gltf: accessor 3 reads past the end of buffer 0".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Problems that still leave a correct render (an unsupported optional extension, a skipped
// degenerate triangle, a non-triangle primitive) are appended to SceneDesc::warnings.
SceneDesc loadGltf(const std::string& path);

}  // namespace pathlab
