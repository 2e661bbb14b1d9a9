// A record of the ray queries a render makes, exactly as they reach Embree (origins already
// offset, tfar as passed) and what Embree answered, in the order each thread made them. It exists
// for one measurement: the BPT's share of the ray-tracing ceiling "for its own mix of rays"
// (issue 11), where the ceiling is these very rays traced again by raw Embree with nothing else
// around them (tests/bench/own_rays_bench.cpp). In a scene with media a connection's transmittance
// is a chain of closest-hit queries through the boundaries, each logged as one. With no log
// attached a query pays only the test of the log pointer (Scene::intersect / visible).
#pragma once

#include "core/math/types.h"

#include <tbb/enumerable_thread_specific.h>

#include <cstddef>
#include <vector>

namespace pathlab {

struct LoggedRay {
  Vec3 o{0.f};
  float tfar = 0.f;  // as passed to Embree
  Vec3 d{0.f};
  // Embree's answer: the ray's tfar after the query (a closest hit's distance; -inf for a blocked
  // shadow ray; tfar unchanged for a miss). A replay of the same ray must give the same bits.
  float tAfter = 0.f;
  bool occluded = false;  // rtcOccluded1 (a shadow ray); otherwise rtcIntersect1
};

class RayLog {
 public:
  void record(const Vec3& o, const Vec3& d, float tfar, float tAfter, bool occluded) {
    perThread_.local().push_back(LoggedRay{o, tfar, d, tAfter, occluded});
  }
  // Each thread's rays in the order that thread traced them, one list per thread that traced any
  // (views into the log: valid until it is cleared or destroyed).
  std::vector<const std::vector<LoggedRay>*> streams() const {
    std::vector<const std::vector<LoggedRay>*> out;
    for (const std::vector<LoggedRay>& rays : perThread_)
      if (!rays.empty()) out.push_back(&rays);
    return out;
  }
  size_t size() const {
    size_t n = 0;
    for (const std::vector<LoggedRay>& rays : perThread_) n += rays.size();
    return n;
  }
  void clear() {
    for (std::vector<LoggedRay>& rays : perThread_) rays.clear();
  }

 private:
  tbb::enumerable_thread_specific<std::vector<LoggedRay>> perThread_;
};

}  // namespace pathlab
