// Builders for in-code test scenes.
#include "tests/support/test_scenes.h"

#include <glm/gtc/matrix_transform.hpp>

namespace pathlab::test {

Material lambertian(float rho, Spectrum emission) {
  Material m;
  m.name = "lambertian";
  m.baseColorFactor = Vec4(rho, rho, rho, 1.f);
  m.metallicFactor = 0.f;
  m.roughnessFactor = 1.f;
  m.specularFactor = 0.f;
  m.emissiveFactor = emission;
  return m;
}

TriangleMesh quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, int material) {
  TriangleMesh mesh;
  mesh.name = "quad";
  mesh.positions = {p0, p1, p2, p3};
  const Vec3 n = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  mesh.normals = {n, n, n, n};
  mesh.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  return mesh;
}

std::vector<TriangleMesh> inwardBox(float h, int material) {
  // Corners; each face listed counter-clockwise as seen from inside the box.
  const Vec3 c[8] = {{-h, -h, -h}, {h, -h, -h}, {h, h, -h}, {-h, h, -h},
                     {-h, -h, h},  {h, -h, h},  {h, h, h},  {-h, h, h}};
  return {quad(c[0], c[1], c[2], c[3], material),   // z = -h, normal +z
          quad(c[5], c[4], c[7], c[6], material),   // z = +h, normal -z
          quad(c[4], c[0], c[3], c[7], material),   // x = -h, normal +x
          quad(c[1], c[5], c[6], c[2], material),   // x = +h, normal -x
          quad(c[4], c[5], c[1], c[0], material),   // y = -h, normal +y
          quad(c[3], c[2], c[6], c[7], material)};  // y = +h, normal -y
}

CameraDesc lookAt(const Vec3& eye, const Vec3& target, const Vec3& up, float yfov) {
  CameraDesc desc;
  desc.cameraToWorld = glm::inverse(glm::lookAt(eye, target, up));
  desc.yfov = yfov;
  return desc;
}

SceneDesc furnace(float rho, float Le) {
  SceneDesc desc;
  desc.path = "furnace";
  desc.materials = {lambertian(rho, Spectrum(Le))};
  desc.meshes = inwardBox(1.f, 0);
  desc.camera = lookAt(Vec3(0.1f, 0.2f, 0.3f), Vec3(1.f, -0.3f, -0.5f), Vec3(0, 1, 0), 1.2f);
  return desc;
}

Material smoothGlass(float ior) {
  Material m;
  m.name = "glass";
  m.transmissionFactor = 1.f;
  m.ior = ior;
  m.roughnessFactor = 0.f;
  m.metallicFactor = 0.f;
  return m;
}

Material mediumBoundary(Spectrum sigmaT, bool scatters, float g) {
  Material m = smoothGlass(1.f);
  m.name = "medium boundary";
  VolumeDesc v;
  v.attenuationColor = glm::exp(-sigmaT);
  v.attenuationDistance = 1.f;
  v.scatters = scatters;
  v.multiscatterColor = Spectrum(1.f);
  v.anisotropy = g;
  m.volume = v;
  return m;
}

std::vector<TriangleMesh> outwardBox(const Vec3& lo, const Vec3& hi, int material) {
  const Vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                     {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
  return {quad(c[3], c[2], c[1], c[0], material),   // z = lo, normal -z
          quad(c[4], c[5], c[6], c[7], material),   // z = hi, normal +z
          quad(c[7], c[3], c[0], c[4], material),   // x = lo, normal -x
          quad(c[1], c[2], c[6], c[5], material),   // x = hi, normal +x
          quad(c[0], c[1], c[5], c[4], material),   // y = lo, normal -y
          quad(c[7], c[6], c[2], c[3], material)};  // y = hi, normal +y
}

SceneDesc foggyFurnace(float rho, float Le, float sigmaT, float g) {
  SceneDesc desc = furnace(rho, Le);
  desc.path = "foggy furnace";
  desc.materials.push_back(mediumBoundary(Spectrum(sigmaT), true, g));
  for (TriangleMesh& m : outwardBox(Vec3(-0.999f), Vec3(0.999f), 1)) desc.meshes.push_back(std::move(m));
  return desc;
}

SceneDesc deltaFurnace(float rho, float Le) {
  SceneDesc desc = furnace(rho, Le);
  desc.path = "delta furnace";
  Material mirror;
  mirror.name = "mirror";
  mirror.metallicFactor = 1.f;
  mirror.roughnessFactor = 0.f;
  desc.materials.push_back(smoothGlass(1.6f));
  desc.materials.push_back(mirror);
  // In front of the furnace's camera, which looks toward (1, -0.3, -0.5) from (0.1, 0.2, 0.3).
  for (TriangleMesh& m : outwardBox(Vec3(0.4f, -0.4f, -0.5f), Vec3(0.8f, 0.f, -0.1f), 1)) desc.meshes.push_back(std::move(m));
  for (TriangleMesh& m : outwardBox(Vec3(0.4f, 0.1f, -0.9f), Vec3(0.7f, 0.4f, -0.6f), 2)) desc.meshes.push_back(std::move(m));
  return desc;
}

SceneDesc floorScene(float rho) {
  SceneDesc desc;
  desc.path = "floor";
  desc.materials = {lambertian(rho)};
  const float F = 50.f;
  desc.meshes = {quad(Vec3(-F, 0, F), Vec3(F, 0, F), Vec3(F, 0, -F), Vec3(-F, 0, -F), 0)};
  return desc;
}

}  // namespace pathlab::test
