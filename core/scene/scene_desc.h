// The plain, renderer-independent description of a scene: what the glTF loader produces and
// Scene::build consumes. World-space triangles, materials, textures, punctual lights, camera.
#pragma once

#include "core/camera/camera_desc.h"
#include "core/lights/environment_desc.h"
#include "core/lights/light_selection.h"
#include "core/scene/material.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pathlab {

struct TriangleMesh {
  std::string name;
  std::vector<Vec3> positions;   // world space
  std::vector<Vec3> normals;     // world space, unit; same count as positions (generated if absent)
  std::vector<Vec2> uvs;         // TEXCOORD_0: empty or same count as positions
  std::vector<Vec2> uvs1;        // TEXCOORD_1: empty or same count as positions
  std::vector<Vec4> colors;      // COLOR_0 (linear rgba): empty or same count as positions
  // World space, unit, w = handedness (bitangent = w cross(normal, tangent), glTF 2.0 sec.
  // 3.7.2.1): empty, or one per position when the material has a normal map.
  std::vector<Vec4> tangents;
  std::vector<uint32_t> indices; // 3 per triangle
  int material = 0;

  size_t triangleCount() const { return indices.size() / 3; }
};

enum class PunctualLightType { Point, Spot, Directional };

// KHR_lights_punctual, in world space. Point and spot `intensity` is radiant intensity
// (W/sr in pathlab's units); directional `intensity` is irradiance (W/m^2) on a surface facing it.
struct PunctualLightDesc {
  std::string name;
  PunctualLightType type = PunctualLightType::Point;
  Spectrum color{1.f};
  float intensity = 1.f;
  Vec3 position{0.f};
  Vec3 direction{0.f, 0.f, -1.f};  // direction the light travels (the node's -z)
  float innerConeAngle = 0.f;
  float outerConeAngle = kPi / 4.f;
};

struct SceneDesc {
  std::string path;               // for messages
  std::vector<TriangleMesh> meshes;
  std::vector<Material> materials;
  std::vector<Texture> textures;
  std::vector<PunctualLightDesc> punctualLights;
  std::optional<CameraDesc> camera;  // none: Scene frames the bounds
  std::vector<std::string> warnings;
  std::shared_ptr<const EnvironmentDesc> environment;  // none: no environment light
  // How next-event estimation chooses among the lights (light_set.h); not the file's: the
  // command line's --light-sampler through LoadOptions.
  LightSelection lightSelection = LightSelection::Auto;
};

}  // namespace pathlab
