// Scene construction (lights, bounds, camera fallback) and ray queries through Embree 3.
#include "core/scene/scene.h"

#include "core/camera/camera.h"
#include "core/scene/alpha_test.h"
#include "core/scene/embree_ray.h"
#include "core/scene/gltf_loader.h"
#include "core/scene/normal_map.h"
#include "core/scene/ray_log.h"
#include "core/math/rng.h"
#include "core/media/volume_grid.h"

#include <fmt/core.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <atomic>
#include <limits>

namespace pathlab {

struct Scene::EmbreeState {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::atomic<int64_t> bytes{0};  // what the device has allocated, as its memory monitor counts
  std::vector<AlphaGeometry> alpha;  // per mesh, the alpha filters' user data (fixed size)
  ~EmbreeState() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// Embree reports its allocations (negative: frees) through a callback, from its build threads.
// Release, and the acquire load after the build (Scene::Scene): the build threads' last touch of
// the counter then happens before whatever the building thread does next, destroying the scene
// included, in a way ThreadSanitizer can see (TBB's own synchronisation is invisible to it).
bool embreeMemory(void* userPtr, ssize_t bytes, bool /*post*/) {
  static_cast<std::atomic<int64_t>*>(userPtr)->fetch_add(int64_t(bytes), std::memory_order_release);
  return true;
}

// Embree reports errors through a C callback: remember the message, throw after the call returns.
void embreeError(void* userPtr, RTCError code, const char* message) {
  if (code != RTC_ERROR_NONE && message) *static_cast<std::string*>(userPtr) = message;
}

RTCScene buildBvh(RTCDevice device, const std::vector<TriangleMesh>& meshes,
                  const std::vector<AlphaGeometry>& alpha) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
  for (size_t m = 0; m < meshes.size(); ++m) {
    const TriangleMesh& mesh = meshes[m];
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i)
      for (int c = 0; c < 3; ++c) v[3 * i + c] = mesh.positions[i][c];
    auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangleCount()));
    std::copy(mesh.indices.begin(), mesh.indices.end(), idx);
    if (alpha[m].material) attachAlphaFilter(geom, &alpha[m]);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene, geom, static_cast<unsigned>(m));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(scene);
  return scene;
}

// The environment's radiance is its texels x the strength (--environment-strength), and its power
// that integral over the sphere x the scene's disc; in float, either can overflow where each factor
// fits (issue 37: 1e35 texels x 1e6 rendered with every environment sample dropped as Inf).
void checkEnvironmentPower(const EnvironmentDesc& desc, const EnvironmentLight& light) {
  const Spectrum power = light.power();
  if (std::isfinite(power.r) && std::isfinite(power.g) && std::isfinite(power.b)) return;
  float brightest = maxComponent(desc.constant);
  for (const Spectrum& t : desc.texels) brightest = std::max(brightest, maxComponent(t));
  throw SceneError(fmt::format("{}: radiance up to {:g} x --environment-strength {:g} overflows a 32-bit float "
                               "over the scene's sphere (its power is not finite); lower the strength",
                               desc.source, brightest, desc.strength));
}

}  // namespace

Scene::Scene(SceneDesc desc)
    : desc_(std::move(desc)), media_(desc_), embree_(std::make_unique<EmbreeState>()) {
  // evalMaterial reads only the base colour and metallic-roughness textures; without them the
  // MaterialPoint, and so the BSDF's lobes, are the same at every point (Scene::bsdf).
  for (const Material& m : desc_.materials) {
    const bool untextured = !m.baseColorTexture.valid() && !m.metallicRoughnessTexture.valid();
    materialUntextured_.push_back(untextured ? 1 : 0);
    materialLobes_.push_back(untextured ? Bsdf(Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, 1.f),
                                               evalMaterial(m, Vec2(0.f), desc_.textures))
                                        : Bsdf());
  }

  // Bounds of everything that can emit or be hit.
  boundsMin_ = Vec3(std::numeric_limits<float>::max());
  boundsMax_ = Vec3(-std::numeric_limits<float>::max());
  for (const TriangleMesh& mesh : desc_.meshes)
    for (const Vec3& p : mesh.positions) {
      boundsMin_ = glm::min(boundsMin_, p);
      boundsMax_ = glm::max(boundsMax_, p);
    }
  for (const PunctualLightDesc& l : desc_.punctualLights)
    if (l.type != PunctualLightType::Directional) {
      boundsMin_ = glm::min(boundsMin_, l.position);
      boundsMax_ = glm::max(boundsMax_, l.position);
    }
  if (boundsMin_.x > boundsMax_.x) throw SceneError(desc_.path + ": the scene has no geometry and no light");
  bounds_.center = 0.5f * (boundsMin_ + boundsMax_);
  bounds_.radius = glm::max(0.5f * glm::length(boundsMax_ - boundsMin_), 1e-6f);

  // Area lights: one per emissive triangle (glTF emissive materials) that emits anything, then
  // punctual lights. A triangle whose texels are all black stays a surface but is no light: its
  // radiance is zero wherever it is hit, so leaving it out of the light set (hit.light = -1)
  // changes no estimate, and the power-proportional choice never wastes a sample on it.
  std::vector<Light> lights;
  std::vector<MediumInterface> lightMedia;  // per light, filled only with media
  std::vector<std::vector<int>> triangleLight(desc_.meshes.size());
  for (size_t m = 0; m < desc_.meshes.size(); ++m) {
    const TriangleMesh& mesh = desc_.meshes[m];
    const Material& mat = desc_.materials.at(static_cast<size_t>(mesh.material));
    if (!mat.isEmissive()) continue;
    const Texture* tex = mat.emissiveTexture.valid()
                             ? &desc_.textures.at(static_cast<size_t>(mat.emissiveTexture.texture))
                             : nullptr;
    const Spectrum emission = mat.emissiveFactor * mat.emissiveStrength;
    // The light reads its emission in the emissive texture's own uv set (emissionUv).
    // A mesh without TEXCOORD_1 reads TEXCOORD_0 for it, as intersect() does (the loader warns).
    const std::vector<Vec2>& uvs =
        mat.emissiveTexture.texCoord == 1 && !mesh.uvs1.empty() ? mesh.uvs1 : mesh.uvs;
    triangleLight[m].assign(mesh.triangleCount(), -1);
    for (size_t t = 0; t < mesh.triangleCount(); ++t) {
      const uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
      const Vec2 uv0 = uvs.empty() ? Vec2(0.f) : uvs[i0];
      const Vec2 uv1 = uvs.empty() ? Vec2(0.f) : uvs[i1];
      const Vec2 uv2 = uvs.empty() ? Vec2(0.f) : uvs[i2];
      Light light = Light::area(mesh.positions[i0], mesh.positions[i1], mesh.positions[i2], uv0, uv1,
                                uv2, emission, tex, mat.doubleSided);
      if (!(maxComponent(light.power()) > 0.f)) continue;
      triangleLight[m][t] = static_cast<int>(lights.size());
      lights.push_back(light);
      if (hasMedia()) lightMedia.push_back(media_.mesh(m));
    }
  }
  for (const PunctualLightDesc& l : desc_.punctualLights) {
    const Spectrum value = l.color * l.intensity;
    switch (l.type) {
      case PunctualLightType::Point: lights.push_back(Light::point(l.position, value)); break;
      case PunctualLightType::Spot:
        lights.push_back(Light::spot(l.position, l.direction, value, l.innerConeAngle, l.outerConeAngle));
        break;
      case PunctualLightType::Directional:
        lights.push_back(Light::directional(l.direction, value, bounds_));
        break;
    }
  }
  if (hasMedia())
    for (const PunctualLightDesc& l : desc_.punctualLights) {
      // A light at infinity starts its subpaths outside every (bounded) volume.
      const int16_t m = static_cast<int16_t>(l.type == PunctualLightType::Directional ? -1 : mediumAt(l.position));
      lightMedia.push_back(MediumInterface{m, m});
    }
  if (desc_.environment) {
    environment_ = std::make_unique<EnvironmentLight>(*desc_.environment, bounds_.center, bounds_.radius);
    checkEnvironmentPower(*desc_.environment, *environment_);
    lights.push_back(Light::environment(environment_.get()));
    if (hasMedia()) lightMedia.push_back(MediumInterface{});
  }
  lightMedia_ = std::move(lightMedia);
  bool anyPower = false;
  for (const Light& l : lights) anyPower = anyPower || luminance(l.power()) > 0.f;
  if (!anyPower) throw SceneError(desc_.path + ": the scene has no light source (no emissive material and no KHR_lights_punctual light)");
  // Separate emitters, for LightSelection::Auto: each emissive mesh copy, punctual light and the
  // environment.
  int emitters = static_cast<int>(desc_.punctualLights.size()) + (desc_.environment ? 1 : 0);
  for (const std::vector<int>& mesh : triangleLight)
    emitters += std::any_of(mesh.begin(), mesh.end(), [](int l) { return l >= 0; }) ? 1 : 0;
  lights_ = LightSet(std::move(lights), std::move(triangleLight), desc_.lightSelection, emitters);

  camera_ = desc_.camera ? *desc_.camera : frameBounds(boundsMin_, boundsMax_);

  embree_->device = rtcNewDevice(nullptr);
  if (!embree_->device) throw SceneError(desc_.path + ": could not create the Embree device");
  std::string embreeMessage;
  rtcSetDeviceErrorFunction(embree_->device, embreeError, &embreeMessage);
  rtcSetDeviceMemoryMonitorFunction(embree_->device, embreeMemory, &embree_->bytes);
  embree_->alpha.resize(desc_.meshes.size());
  for (size_t m = 0; m < desc_.meshes.size(); ++m) {
    const Material& mat = desc_.materials.at(static_cast<size_t>(desc_.meshes[m].material));
    if (mat.hasAlphaTest()) embree_->alpha[m] = AlphaGeometry{&desc_.meshes[m], &mat, &desc_.textures};
  }
  embree_->scene = buildBvh(embree_->device, desc_.meshes, embree_->alpha);
  (void)embree_->bytes.load(std::memory_order_acquire);  // see embreeMemory
  rtcSetDeviceErrorFunction(embree_->device, nullptr, nullptr);
  if (rtcGetDeviceError(embree_->device) != RTC_ERROR_NONE)
    throw SceneError(desc_.path + ": Embree could not build the scene: " + embreeMessage);
}

Scene::~Scene() = default;

size_t Scene::triangleCount() const {
  size_t n = 0;
  for (const TriangleMesh& m : desc_.meshes) n += m.triangleCount();
  return n;
}

size_t Scene::geometryBytes() const {
  size_t bytes = 0;
  for (const TriangleMesh& m : desc_.meshes) {
    bytes += m.positions.capacity() * sizeof(Vec3) + m.normals.capacity() * sizeof(Vec3) +
             (m.uvs.capacity() + m.uvs1.capacity()) * sizeof(Vec2) +
             (m.colors.capacity() + m.tangents.capacity()) * sizeof(Vec4) +
             m.indices.capacity() * sizeof(uint32_t);
  }
  const int64_t embree = embree_->bytes.load(std::memory_order_relaxed);
  return bytes + size_t(std::max<int64_t>(embree, 0)) + lights_.size() * sizeof(Light);
}

void* Scene::embreeHandle() const { return embree_->scene; }

Bsdf Scene::bsdf(int material, const ShadingInputs& at, const Vec3& ns, const Vec3& ng) const {
  const auto m = static_cast<size_t>(material);
  if (materialUntextured_[m] && at.color == Spectrum(1.f)) return Bsdf(ns, ng, materialLobes_[m]);
  return Bsdf(ns, ng, evalMaterial(desc_.materials[m], at, desc_.textures));
}

namespace {
// Out of line and cold, reading the query back from Embree's ray (which keeps origin and
// direction; tfar is its answer): with no log attached a query pays only the pointer's test.
[[gnu::noinline, gnu::cold]] void logQuery(RayLog* log, const RTCRay& answered, float tfar, bool occluded) {
  log->record(Vec3(answered.org_x, answered.org_y, answered.org_z),
              Vec3(answered.dir_x, answered.dir_y, answered.dir_z), tfar, answered.tfar, occluded);
}
}  // namespace

std::optional<SurfaceHit> Scene::intersect(const Ray& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = embreeRayHit(ray.o, ray.d, ray.tMax);
  rtcIntersect1(embree_->scene, &context, &rh);
  if (RayLog* log = rayLog_.load(std::memory_order_relaxed)) [[unlikely]]
    logQuery(log, rh.ray, ray.tMax, false);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;

  const TriangleMesh& mesh = desc_.meshes[rh.hit.geomID];
  const uint32_t* tri = &mesh.indices[3 * rh.hit.primID];
  const float b1 = rh.hit.u, b2 = rh.hit.v, b0 = 1.f - b1 - b2;
  const Vec3 &p0 = mesh.positions[tri[0]], &p1 = mesh.positions[tri[1]], &p2 = mesh.positions[tri[2]];

  SurfaceHit hit;
  hit.t = rh.ray.tfar;
  // Barycentric interpolation is more accurate than o + t d (pbrt-v4 sec. 6.8).
  hit.p = b0 * p0 + b1 * p1 + b2 * p2;
  hit.pError = interpolationError(b0, p0, b1, p1, b2, p2);
  hit.ng = glm::normalize(glm::cross(p1 - p0, p2 - p0));
  auto interpolate = [&](const auto& values) {
    return b0 * values[tri[0]] + b1 * values[tri[1]] + b2 * values[tri[2]];
  };
  if (!mesh.uvs.empty()) hit.uv = interpolate(mesh.uvs);
  hit.uv1 = mesh.uvs1.empty() ? hit.uv : interpolate(mesh.uvs1);
  if (!mesh.colors.empty()) hit.color = Spectrum(interpolate(mesh.colors));
  hit.ns = hit.ng;
  if (!mesh.normals.empty()) {
    Vec3 ns = interpolate(mesh.normals);
    const float len = glm::length(ns);
    if (len > 1e-8f && std::isfinite(len)) {
      ns /= len;
      if (!mesh.tangents.empty()) {
        // A normal map perturbs the shading normal; the BSDF's shading-normal handling (and
        // Veach's adjoint correction on light subpaths) takes it from here like any other.
        const Vec3 mapped = mappedNormal(desc_.materials[static_cast<size_t>(mesh.material)],
                                         ShadingInputs{hit.uv, hit.uv1, hit.color}, ns,
                                         interpolate(mesh.tangents), desc_.textures);
        // A mapped normal below the surface (on the far side of ng from the interpolated one)
        // has no meaning for a one-sided shading frame: the interpolated normal is kept there.
        if (glm::dot(mapped, hit.ng) * glm::dot(ns, hit.ng) > 0.f) ns = mapped;
      }
      hit.ns = glm::dot(ns, hit.ng) < 0.f ? -ns : ns;
    }
  }
  hit.meshId = rh.hit.geomID;
  hit.primId = rh.hit.primID;
  hit.material = mesh.material;
  hit.light = lights_.lightOfTriangle(hit.meshId, hit.primId);
  if (hasMedia()) {
    hit.media = media_.mesh(hit.meshId);
    hit.indexMatched = media_.indexMatched(hit.meshId);
  }
  return hit;
}

namespace {
bool occluded(RTCScene scene, const std::atomic<RayLog*>& rayLog, const Vec3& o, const Vec3& d, float tfar) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r = embreeRay(o, d, tfar);
  rtcOccluded1(scene, &context, &r);
  if (RayLog* log = rayLog.load(std::memory_order_relaxed)) [[unlikely]]
    logQuery(log, r, tfar, true);
  return r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
}
}  // namespace

bool Scene::visible(const Vec3& a, const Vec3& na, const Vec3& ea, const Vec3& b, const Vec3& nb,
                    const Vec3& eb) const {
  const Vec3 oa = offsetRayOrigin(a, ea, na, b - a);
  const Vec3 ob = offsetRayOrigin(b, eb, nb, a - b);
  // Shorten at the far end too: rtcOccluded1 makes no promise about hits exactly at tfar.
  return !occluded(embree_->scene, rayLog_, oa, ob - oa, 1.f - 1e-4f);
}

bool Scene::visibleToInfinity(const Vec3& p, const Vec3& n, const Vec3& e, const Vec3& dir) const {
  return !occluded(embree_->scene, rayLog_, offsetRayOrigin(p, e, n, dir), dir, std::numeric_limits<float>::infinity());
}

namespace {
// More crossings than any sensible nesting of volumes: a segment grazing along a boundary's
// triangles ends as blocked rather than looping.
constexpr int kMaxBoundaryCrossings = 64;
}  // namespace

Spectrum Scene::transmittance(const Vec3& a, const Vec3& na, const Vec3& ea, const Vec3& b, const Vec3& nb,
                              const Vec3& eb, int medium) const {
  const Vec3 o = offsetRayOrigin(a, ea, na, b - a);
  const Vec3 ob = offsetRayOrigin(b, eb, nb, a - b);
  const Vec3 d = ob - o;
  const float length = glm::length(d);
  if (!(length > 0.f)) return Spectrum(1.f);
  return transmittanceAlong(o, d / length, &ob, medium);
}

Spectrum Scene::transmittanceToInfinity(const Vec3& p, const Vec3& n, const Vec3& e, const Vec3& dir, int medium) const {
  return transmittanceAlong(offsetRayOrigin(p, e, n, dir), dir, nullptr, medium);
}

// The transmittance of medium `medium` along o + t dir, t in [0, distance): closed form in a
// homogeneous medium; ratio tracking's estimate in a heterogeneous one (volume_grid.h), its random
// numbers from a hash of the segment, so that the same connection always gets the same estimate
// (a replayed sample, the inspector's and MLT's re-evaluations) and different segments independent
// ones.
Spectrum Scene::segmentTransmittance(int medium, const Vec3& o, const Vec3& dir, float distance) const {
  const HomogeneousMedium& m = media_[medium];
  const VolumeGrid* grid = media_.grid(medium);
  if (!grid) return m.transmittance(distance);
  uint64_t key = 0x5bd1e995ULL;
  for (const float x : {o.x, o.y, o.z, dir.x, dir.y, dir.z, distance}) key = mixBits(key ^ std::bit_cast<uint32_t>(x));
  Pcg32 rng(key, mixBits(key ^ 0x9e3779b97f4a7c15ULL));
  return ratioTrack(m, *grid, o, dir, distance, rng);
}

Spectrum Scene::transmittanceAlong(Vec3 o, const Vec3& dir, const Vec3* end, int medium) const {
  Spectrum T(1.f);
  for (int crossing = 0; crossing < kMaxBoundaryCrossings; ++crossing) {
    const float distance = end ? glm::length(*end - o) : std::numeric_limits<float>::infinity();
    // As in `visible`: no promise about hits exactly at the far end.
    const std::optional<SurfaceHit> hit = intersect(Ray{o, dir, end ? distance * (1.f - 1e-4f) : distance});
    if (!hit) return medium >= 0 ? T * segmentTransmittance(medium, o, dir, distance) : T;
    if (!hit->indexMatched) return Spectrum(0.f);
    if (medium >= 0) T *= segmentTransmittance(medium, o, dir, hit->t);
    if (isBlack(T)) return T;
    medium = hit->media.toward(hit->ng, dir);
    o = offsetRayOrigin(hit->p, hit->pError, hit->ng, dir);
  }
  return Spectrum(0.f);
}

}  // namespace pathlab
