// The loader's whole-scene checks on the SceneDesc it built: something emits, and the quantities
// the renderer derives from the whole scene (its extent, the lights' total power) fit in floats.
#include "core/scene/gltf_internal.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab::gltf {
namespace {

// A scene that emits nothing renders black whatever the estimator.
void checkHasEmitter(const SceneDesc& desc) {
  if (desc.environment || hasEmitter(desc)) return;
  throw LoadError(
      "no light source (no triangle has an emissive material and no "
      "KHR_lights_punctual light is in the scene)");
}

struct Extent {
  Vec3 min{std::numeric_limits<float>::max()};
  Vec3 max{-std::numeric_limits<float>::max()};
  void add(const Vec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  bool empty() const { return min.x > max.x; }
};

// Every squared distance between two points of the scene (the geometry term of each
// connection, Scene's bounding radius) is at most the squared diagonal, computed here in float
// as the renderer does: if it is finite, they all are.
Extent checkExtent(const SceneDesc& desc) {
  Extent e;
  for (const TriangleMesh& mesh : desc.meshes) {
    for (const Vec3& p : mesh.positions) e.add(p);
  }
  for (const PunctualLightDesc& light : desc.punctualLights) {
    if (light.type != PunctualLightType::Directional) e.add(light.position);
  }
  if (desc.camera) e.add(Vec3(desc.camera->cameraToWorld[3]));
  if (e.empty()) return e;
  const Vec3 diagonal = e.max - e.min;
  if (!std::isfinite(glm::dot(diagonal, diagonal))) {
    const double span = glm::length(glm::dvec3(e.max) - glm::dvec3(e.min));
    throw LoadError("the scene spans " + formatNumber(span) +
                    " units (geometry, lights and camera): its squared extent " + overflowText() +
                    "; scale it down");
  }
  return e;
}

// Lights are chosen in proportion to their power (Light::power, in float); bounded above here
// (two-sided emitters, a point light's full sphere).
void checkEmittedPower(const SceneDesc& desc, const Extent& extent) {
  double power = 0.0;
  for (const TriangleMesh& mesh : desc.meshes) {
    const Material& m = desc.materials[size_t(mesh.material)];
    if (!m.isEmissive()) continue;
    double area = 0.0;
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t* i = &mesh.indices[3 * t];
      const Vec3& p0 = mesh.positions[i[0]];
      area += 0.5 * double(glm::length(glm::cross(mesh.positions[i[1]] - p0, mesh.positions[i[2]] - p0)));
    }
    power += 2.0 * kPi * area * double(maxComponent(m.emissiveFactor * m.emissiveStrength));
  }
  const double radius = extent.empty() ? 0.0 : 0.5 * glm::length(glm::dvec3(extent.max - extent.min));
  for (const PunctualLightDesc& light : desc.punctualLights) {
    const double value = double(maxComponent(light.color * light.intensity));
    power += light.type == PunctualLightType::Directional ? kPi * radius * radius * value
                                                          : 4.0 * kPi * value;
  }
  if (!(power <= double(std::numeric_limits<float>::max()))) {
    throw LoadError("the lights' total emitted power " + formatNumber(power) + " " +
                    overflowText() + "; lower the emission or the scene's size");
  }
}

}  // namespace

bool hasEmitter(const SceneDesc& desc) {
  for (const PunctualLightDesc& light : desc.punctualLights) {
    if (light.intensity > 0.f && maxComponent(light.color) > 0.f) return true;
  }
  // Each emissive texture is read once, however many meshes use it.
  std::vector<int> checked;
  for (const TriangleMesh& mesh : desc.meshes) {
    const Material& m = desc.materials[size_t(mesh.material)];
    if (!m.isEmissive()) continue;
    const int texture = m.emissiveTexture.texture;
    if (!m.emissiveTexture.valid()) return true;
    if (std::find(checked.begin(), checked.end(), texture) != checked.end()) continue;
    checked.push_back(texture);
    if (maxComponent(Spectrum(desc.textures[size_t(texture)].average())) > 0.f) return true;
  }
  return false;
}

bool hasLamp(const SceneDesc& desc) {
  for (const PunctualLightDesc& light : desc.punctualLights)
    if (light.intensity > 0.f && maxComponent(light.color) > 0.f) return true;
  for (const TriangleMesh& mesh : desc.meshes) {
    const Material& m = desc.materials[size_t(mesh.material)];
    if (m.isEmissive() && !m.emissiveTexture.valid()) return true;
  }
  return false;
}

void checkScene(const SceneDesc& desc, bool requireEmitter) {
  if (requireEmitter) checkHasEmitter(desc);
  checkEmittedPower(desc, checkExtent(desc));
}

}  // namespace pathlab::gltf
