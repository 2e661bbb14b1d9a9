// The immutable scene a render reads: world-space meshes in an Embree BVH, materials, textures,
// lights and the camera description. Built once from a SceneDesc; safe to share across threads.
#pragma once

#include "core/bsdf/bsdf.h"
#include "core/lights/light_set.h"
#include "core/math/ray.h"
#include "core/scene/scene_media.h"
#include "core/scene/scene_desc.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace pathlab {

class RayLog;  // core/scene/ray_log.h: kept out of this header, which nearly every file includes

class Scene {
 public:
  // Throws SceneError (naming desc.path) if the scene cannot be rendered: no triangles and no
  // punctual light, or no emitter at all (the environment counts).
  explicit Scene(SceneDesc desc);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  std::optional<SurfaceHit> intersect(const Ray& ray) const;
  // True when nothing blocks the open segment between two points. Each end is moved off its
  // surface along its normal by its error bound (offsetRayOrigin); zero normals and bounds for
  // points not on a surface (lens, punctual light).
  bool visible(const Vec3& a, const Vec3& na, const Vec3& ea, const Vec3& b, const Vec3& nb, const Vec3& eb) const;
  // True when nothing blocks the ray from a surface point toward infinity (directional lights).
  bool visibleToInfinity(const Vec3& p, const Vec3& n, const Vec3& e, const Vec3& dir) const;

  // Participating media (issue 16). A scene without them pays nothing: hits carry no interface,
  // and the estimators take their surface-only paths.
  bool hasMedia() const { return !media_.empty(); }
  const HomogeneousMedium& medium(int i) const { return media_[i]; }
  // Medium i's density grid (issue 35), nullptr when it is homogeneous: then medium(i) holds its
  // coefficients at density 1.
  const VolumeGrid* mediumGrid(int i) const { return media_.grid(i); }
  const SceneMedia& media() const { return media_; }
  // The innermost medium containing p (-1: none); a test against every volume's triangles, for
  // set-up (a camera's position), not per sample.
  int mediumAt(const Vec3& p) const { return media_.mediumAt(p); }
  // The media either side of light `light` (an area light's mesh; a punctual light's
  // surroundings on both sides; none at infinity).
  MediumInterface lightMedia(int light) const {
    return lightMedia_.empty() ? MediumInterface{} : lightMedia_[static_cast<size_t>(light)];
  }
  // Transmittance of the open segment between two points (offset as in `visible`) whose first
  // part lies in `medium`: zero when a surface blocks it; index-matched boundaries are crossed,
  // each changing the medium, and every medium's T_r multiplied in (the seed's T_r per edge).
  Spectrum transmittance(const Vec3& a, const Vec3& na, const Vec3& ea, const Vec3& b, const Vec3& nb, const Vec3& eb,
                         int medium) const;
  // The same from a point toward infinity: zero in a medium that extinguishes.
  Spectrum transmittanceToInfinity(const Vec3& p, const Vec3& n, const Vec3& e, const Vec3& dir, int medium) const;

  const std::vector<TriangleMesh>& meshes() const { return desc_.meshes; }
  const std::vector<Material>& materials() const { return desc_.materials; }
  const std::vector<Texture>& textures() const { return desc_.textures; }
  const Material& material(int i) const { return desc_.materials[static_cast<size_t>(i)]; }
  // The BSDF of material `material` at a surface point (uv, shading and geometric normal):
  // Bsdf(ns, ng, evalMaterial(...)). For a material without textures the material evaluation and
  // the lobe set-up are done once, here at construction, and only the frame is built per point.
  Bsdf bsdf(int material, const ShadingInputs& at, const Vec3& ns, const Vec3& ng) const;
  Bsdf bsdf(int material, Vec2 uv, const Vec3& ns, const Vec3& ng) const {
    return bsdf(material, ShadingInputs{uv, uv, Spectrum(1.f)}, ns, ng);
  }
  // The texture coordinates an area light of `material` reads its emission at (the set its
  // emissiveTexture uses): what Light::radiance takes for a point hit on it.
  Vec2 emissionUv(int material, Vec2 uv0, Vec2 uv1) const {
    return ShadingInputs{uv0, uv1, Spectrum(1.f)}.uv(this->material(material).emissiveTexture);
  }
  const LightSet& lights() const { return lights_; }
  const CameraDesc& cameraDesc() const { return camera_; }
  const SceneBounds& bounds() const { return bounds_; }
  Vec3 boundsMin() const { return boundsMin_; }
  Vec3 boundsMax() const { return boundsMax_; }
  const std::string& path() const { return desc_.path; }
  const std::vector<std::string>& warnings() const { return desc_.warnings; }
  size_t triangleCount() const;
  // Approximate memory of the geometry: the world-space meshes, Embree's copy and BVH (as its
  // memory monitor counts them) and the lights.
  size_t geometryBytes() const;
  // The RTCScene, for the ray-throughput ceiling benchmark (tests/bench); renderers use intersect/visible.
  void* embreeHandle() const;
  // Records every ray query into `log` from now on (nullptr: stop). For the ceiling benchmark's
  // replay of a render's own rays (ray_log.h). Atomic, so attaching during a render is no data
  // race, but a render then logs only part of its rays: attach between passes.
  void setRayLog(RayLog* log) const { rayLog_.store(log, std::memory_order_relaxed); }

 private:
  SceneDesc desc_;
  SceneMedia media_;                        // after desc_: it reads its meshes
  std::vector<MediumInterface> lightMedia_;  // per light, with media only
  std::vector<Bsdf> materialLobes_;          // per material, for those without textures
  std::vector<uint8_t> materialUntextured_;  // materialLobes_[i] is valid
  std::unique_ptr<EnvironmentLight> environment_;  // LightSet's environment light refers to it
  LightSet lights_;
  CameraDesc camera_;
  SceneBounds bounds_;
  Vec3 boundsMin_{0.f}, boundsMax_{0.f};
  // Both transmittances: from o along dir to *end (nullptr: to infinity), starting in `medium`.
  Spectrum transmittanceAlong(Vec3 o, const Vec3& dir, const Vec3* end, int medium) const;
  Spectrum segmentTransmittance(int medium, const Vec3& o, const Vec3& dir, float distance) const;
  struct EmbreeState;
  std::unique_ptr<EmbreeState> embree_;  // after desc_: its filters read the meshes
  mutable std::atomic<RayLog*> rayLog_{nullptr};
};

}  // namespace pathlab
