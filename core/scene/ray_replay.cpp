// replayRays: logged ray queries traced again through raw Embree, checked against the logged answers.
#include "core/scene/ray_replay.h"

#include "core/scene/embree_ray.h"

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
      RTCRay ray = embreeRay(r->o, r->d, r->tfar);
      rtcOccluded1(rtcScene, &context, &ray);
      tAfter = ray.tfar;
    } else {
      RTCRayHit rh = embreeRayHit(r->o, r->d, r->tfar);
      rtcIntersect1(rtcScene, &context, &rh);
      tAfter = rh.ray.tfar;
    }
    mismatches += std::bit_cast<uint32_t>(tAfter) != std::bit_cast<uint32_t>(r->tAfter);
  }
  return mismatches;
}

}  // namespace pathlab
