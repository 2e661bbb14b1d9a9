// Random connections for the tests of per-path quantities (technique masks, densities, weights):
// camera and light subpaths through random film positions of a small camera, and every (s, t)
// that formConnection can form on them.
#pragma once

#include "core/bpt/connect.h"
#include "core/bpt/mis.h"

#include <functional>

namespace pathlab::test {

// Calls visit(path, s, t) for every connectable technique up to maxLength on `samples` random
// subpath pairs of `scene` seen through `camera`, the random numbers from `rng`.
void forEachConnection(const Scene& scene, const Camera& camera, int maxLength, int samples, Pcg32 rng,
                       const std::function<void(const MisPath& path, int s, int t)>& visit);

}  // namespace pathlab::test
