// glTF 2.0 (.gltf / .glb) -> SceneDesc through tinygltf: the whole node hierarchy of the default
// scene flattened to world-space triangles, metallic-roughness materials with the supported
// KHR_materials_* extensions, KHR_lights_punctual lights and the first perspective camera.
#pragma once

#include "core/scene/scene_desc.h"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

namespace pathlab {

// Thrown for any input pathlab cannot render correctly. what() is one line that names the file
// and the problem, e.g. "scenes/box.gltf: accessor 3 reads past the end of buffer 0".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  // Triangles after instancing (every node's copy of its mesh counts), checked before anything
  // is built. The world-space copies and the Embree BVH take about 120 bytes a triangle
  // (measured on a 129 k-triangle model), so the default of 50 M is about 6 GB: as much as a
  // workstation gives one process, and 50 times the largest model pathlab is tested on
  // (MetalRoughSpheresNoTextures, 1.04 M; the bundled scenes have under 10 k).
  uint64_t maxTriangles = 50'000'000;
  // Refuse a scene in which nothing emits ("no light source"). Off: the description of an unlit
  // model, to inspect (tests) or to light otherwise; Scene still refuses to render it.
  bool requireEmitter = true;
  // An environment light added to the scene (the command line's --environment), lights of the
  // file or not.
  std::shared_ptr<const EnvironmentDesc> environment;
  // A file with no light of its own, and no `environment`, is lit by a uniform white environment
  // of radiance 1 (as Blender's default world), with a notice among the warnings, instead of being
  // refused. Off here, on for the command line (--no-default-light turns it off).
  bool defaultLight = false;
  // Copied to SceneDesc::lightSelection.
  LightSelection lightSelection = LightSelection::Auto;
};

// Problems that still leave a correct render (an unsupported optional extension, a skipped
// degenerate triangle, a non-triangle primitive) are appended to SceneDesc::warnings.
SceneDesc loadGltf(const std::string& path, const LoadOptions& options = {});

}  // namespace pathlab
