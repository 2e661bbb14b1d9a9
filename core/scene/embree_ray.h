// The Embree rays pathlab traces, set up in one place: Scene::intersect and Scene::visible build
// theirs here, and so do the replay of logged rays (ray_replay.cpp) and the ceiling benchmark, so
// what they measure is the same query (tnear 0, every mask bit, no hit yet).
#pragma once

#include "core/math/types.h"

#include <embree3/rtcore.h>

namespace pathlab {

// Fills ray fields in place, as the callers' own RTCRay / RTCRayHit (value-initialised) hold them:
// no temporary to copy (which cost the renderer instructions on every query).
inline void setEmbreeRay(RTCRay& r, const Vec3& o, const Vec3& d, float tfar) {
  r.org_x = o.x;
  r.org_y = o.y;
  r.org_z = o.z;
  r.dir_x = d.x;
  r.dir_y = d.y;
  r.dir_z = d.z;
  r.tnear = 0.f;
  r.tfar = tfar;
  r.mask = 0xFFFFFFFFu;
}

inline RTCRay embreeRay(const Vec3& o, const Vec3& d, float tfar) {
  RTCRay r{};
  setEmbreeRay(r, o, d, tfar);
  return r;
}

inline RTCRayHit embreeRayHit(const Vec3& o, const Vec3& d, float tfar) {
  RTCRayHit rh{};
  setEmbreeRay(rh.ray, o, d, tfar);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

}  // namespace pathlab
