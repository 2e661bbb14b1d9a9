#include "core/scene/ray_replay.h"

#include <embree3/rtcore.h>

#include <bit>

namespace pathlab {

size_t replayRays(const Scene& scene, const LoggedRay* rays, size_t count) {
  auto rtcScene = static_cast<RTCScene>(scene.embreeHandle());
  size_t mismatches = 0;
  for (const LoggedRay* r = rays; r != rays + count; ++r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    float tAfter = 0.f;
    if (r->occluded) {
      RTCRay ray{};
      ray.org_x = r->o.x, ray.org_y = r->o.y, ray.org_z = r->o.z;
      ray.dir_x = r->d.x, ray.dir_y = r->d.y, ray.dir_z = r->d.z;
      ray.tnear = 0.f;
      ray.tfar = r->tfar;
      ray.mask = 0xFFFFFFFFu;
      rtcOccluded1(rtcScene, &context, &ray);
      tAfter = ray.tfar;
    } else {
      RTCRayHit rh{};
      rh.ray.org_x = r->o.x, rh.ray.org_y = r->o.y, rh.ray.org_z = r->o.z;
      rh.ray.dir_x = r->d.x, rh.ray.dir_y = r->d.y, rh.ray.dir_z = r->d.z;
      rh.ray.tnear = 0.f;
      rh.ray.tfar = r->tfar;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(rtcScene, &context, &rh);
      tAfter = rh.ray.tfar;
    }
    mismatches += std::bit_cast<uint32_t>(tAfter) != std::bit_cast<uint32_t>(r->tAfter);
  }
  return mismatches;
}

}  // namespace pathlab
