// Builders for the in-code scenes of the bidirectional agreement and delta tests.
#include "tests/support/bpt_scenes.h"

#include "tests/support/test_scenes.h"

#include <cmath>

namespace pathlab::test {

Material mirror(float reflectance) {
  Material m;
  m.name = "mirror";
  m.baseColorFactor = Vec4(reflectance, reflectance, reflectance, 1.f);
  m.metallicFactor = 1.f;
  m.roughnessFactor = 0.f;
  return m;
}

Material glass(float ior) {
  Material m;
  m.name = "glass";
  m.baseColorFactor = Vec4(1.f);
  m.metallicFactor = 0.f;
  m.roughnessFactor = 0.f;
  m.transmissionFactor = 1.f;
  m.ior = ior;
  return m;
}

TriangleMesh uvSphere(const Vec3& centre, float radius, int material, int segments, int rings) {
  TriangleMesh mesh;
  mesh.name = "sphere";
  mesh.material = material;
  for (int j = 0; j <= rings; ++j) {
    const float theta = kPi * static_cast<float>(j) / static_cast<float>(rings);
    for (int i = 0; i <= segments; ++i) {
      const float phi = 2.f * kPi * static_cast<float>(i) / static_cast<float>(segments);
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(centre + radius * n);
      mesh.normals.push_back(n);
      mesh.uvs.push_back(Vec2(static_cast<float>(i) / static_cast<float>(segments),
                              static_cast<float>(j) / static_cast<float>(rings)));
    }
  }
  const auto index = [&](int i, int j) { return static_cast<uint32_t>(j * (segments + 1) + i); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < segments; ++i) {
      // Counter-clockwise seen from outside (phi grows toward -z seen from +y).
      const uint32_t a = index(i, j), b = index(i, j + 1), c = index(i + 1, j + 1), d = index(i + 1, j);
      if (j != 0) mesh.indices.insert(mesh.indices.end(), {a, b, d});
      if (j != rings - 1) mesh.indices.insert(mesh.indices.end(), {d, b, c});
    }
  return mesh;
}

SceneDesc deltaScene(DeltaLight light) {
  SceneDesc desc;
  desc.path = light == DeltaLight::Area ? "delta scene (area light)" : "delta scene (point light)";
  desc.materials = {lambertian(0.5f), mirror(0.9f), glass(1.5f), lambertian(0.f, Spectrum(1.5f))};
  const float F = 2.5f;
  desc.meshes.push_back(quad(Vec3(-F, 0, F), Vec3(F, 0, F), Vec3(F, 0, -1.3f), Vec3(-F, 0, -1.3f), 0));  // floor
  // Back wall, facing the camera, its lower edge 0.2 m above and behind the floor's far edge.
  desc.meshes.push_back(
      quad(Vec3(-F, 0.2f, -1.5f), Vec3(F, 0.2f, -1.5f), Vec3(F, 2.5f, -1.5f), Vec3(-F, 2.5f, -1.5f), 0));
  // Mirror on the left, facing +x and toward the camera, 0.1 m above the floor.
  const Vec3 a(-1.3f, 0.1f, 0.4f), b(-0.8f, 0.1f, -1.1f), up(0.f, 1.4f, 0.f);
  desc.meshes.push_back(quad(a, b, b + up, a + up, 1));
  desc.meshes.push_back(uvSphere(Vec3(0.45f, 0.5f, -0.3f), 0.4f, 2));  // 0.1 m above the floor
  const Vec3 lightCentre(-0.2f, 2.4f, 0.f);
  if (light == DeltaLight::Area) {
    const float h = 0.5f;
    const Vec3 c = lightCentre;
    desc.meshes.push_back(quad(Vec3(c.x - h, c.y, c.z - h), Vec3(c.x + h, c.y, c.z - h), Vec3(c.x + h, c.y, c.z + h),
                               Vec3(c.x - h, c.y, c.z + h), 3));  // facing -y
  } else {
    PunctualLightDesc point;
    point.type = PunctualLightType::Point;
    point.intensity = 3.f;
    point.position = lightCentre;
    desc.punctualLights = {point};
  }
  desc.camera = lookAt(Vec3(0.f, 1.2f, 3.2f), Vec3(-0.1f, 0.45f, -0.4f), Vec3(0, 1, 0), 0.75f);
  return desc;
}

SceneDesc integratingSphere() {
  SceneDesc desc;
  desc.path = "integrating sphere";
  Material red = lambertian(0.f);
  red.baseColorFactor = Vec4(0.7f, 0.4f, 0.3f, 1.f);
  desc.materials = {lambertian(0.7f), lambertian(0.f, Spectrum(2.f)), red};
  const int segments = 48, rings = 24, capRings = 4;  // 4 of 24 rings: 0.52 rad from the pole
  // Split the shell into the emitting cap and the rest, both facing inward (reversed winding and
  // normals of the outward sphere).
  TriangleMesh shell = uvSphere(Vec3(0.f), 2.f, 0, segments, rings);
  for (Vec3& n : shell.normals) n = -n;
  TriangleMesh cap = shell, wall = shell;
  cap.material = 1;
  cap.indices.clear();
  wall.indices.clear();
  for (size_t i = 0; i < shell.indices.size(); i += 3) {
    const uint32_t a = shell.indices[i], b = shell.indices[i + 1], c = shell.indices[i + 2];
    const bool inCap = shell.positions[a].y > 2.f * std::cos(kPi * capRings / rings) - 1e-4f &&
                       shell.positions[b].y > 2.f * std::cos(kPi * capRings / rings) - 1e-4f &&
                       shell.positions[c].y > 2.f * std::cos(kPi * capRings / rings) - 1e-4f;
    (inCap ? cap : wall).indices.insert((inCap ? cap : wall).indices.end(), {a, c, b});
  }
  desc.meshes = {wall, cap, uvSphere(Vec3(0.f, -0.3f, 0.f), 0.5f, 2)};
  desc.camera = lookAt(Vec3(0.2f, 0.2f, 1.7f), Vec3(0.f, 0.1f, 0.f), Vec3(0, 1, 0), 1.6f);
  return desc;
}

}  // namespace pathlab::test
