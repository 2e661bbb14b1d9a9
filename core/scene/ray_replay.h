// Logged ray queries (ray_log.h) traced again through raw Embree, with the same ray fields and
// context Scene::intersect and Scene::visible give them and nothing else: the ceiling benchmark's
// inner loop (tests/bench/own_rays_bench.cpp), and the tests' proof that the log holds what Embree
// received.
#pragma once

#include "core/scene/ray_log.h"
#include "core/scene/scene.h"

#include <cstddef>

namespace pathlab {

// Traces rays[0, count) in order; returns how many answers (tfar after the query) differ in any
// bit from the logged ones: zero when the log is faithful.
size_t replayRays(const Scene& scene, const LoggedRay* rays, size_t count);

}  // namespace pathlab
