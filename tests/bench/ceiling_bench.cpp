// The ray-tracing ceiling: raw Embree throughput of incoherent single rays (rtcIntersect1 and
// rtcOccluded1) on every bundled scene with the threads the integrators get. An integrator's
// rays/s divided by this is the fraction of the machine's ray-tracing limit it reaches.
//
// Rays: origins uniform in the scene's bounding box, directions uniform on the sphere, tfar = inf,
// pre-generated (2^18 per scene, 10 MB) so the loop measures Embree alone. They are as incoherent
// as a path tracer's secondary rays but start anywhere in the box rather than on surfaces: in a
// closed room (the Cornell box, the lamp room) nearly every ray hits, in open scenes (veach-mis,
// caustic) some start outside the geometry and miss, which is cheaper; the hit fraction is
// reported beside each figure. The same rays serve both queries so their rates compare directly.
#include "core/math/rng.h"
#include "core/scene/embree_ray.h"
#include "core/sampling/warp.h"
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>
#include <embree3/rtcore.h>
#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <limits>
#include <map>
#include <mutex>

namespace pathlab::bench {

namespace {

constexpr size_t kRays = size_t{1} << 18;
constexpr size_t kGrain = 1024;

struct RaySet {
  std::vector<Vec3> origins, directions;
};

const RaySet& raysFor(const std::string& sceneName) {
  static std::mutex mutex;
  static std::map<std::string, RaySet> sets;
  std::lock_guard lock(mutex);
  RaySet& set = sets[sceneName];
  if (set.origins.empty()) {
    const Scene& scene = benchScene(sceneName);
    const Vec3 lo = scene.boundsMin(), extent = scene.boundsMax() - scene.boundsMin();
    Pcg32 rng(0x5eed, 0xce11);
    for (size_t i = 0; i < kRays; ++i) {
      set.origins.push_back(lo + extent * Vec3(rng.next1D(), rng.next1D(), rng.next1D()));
      set.directions.push_back(sampleUniformSphere(rng.next2D()));
    }
  }
  return set;
}

// Traces every ray once; returns the number that hit something.
size_t traceAll(RTCScene scene, const RaySet& set, bool occluded) {
  return tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, kRays, kGrain), size_t{0},
      [&](const tbb::blocked_range<size_t>& range, size_t hits) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);  // incoherent by default
        for (size_t i = range.begin(); i < range.end(); ++i) {
          if (occluded) {
            RTCRay r = embreeRay(set.origins[i], set.directions[i], std::numeric_limits<float>::infinity());
            rtcOccluded1(scene, &context, &r);
            hits += r.tfar < 0.f;  // Embree sets tfar to -inf on a hit
          } else {
            RTCRayHit rh = embreeRayHit(set.origins[i], set.directions[i], std::numeric_limits<float>::infinity());
            rtcIntersect1(scene, &context, &rh);
            hits += rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
          }
        }
        return hits;
      },
      [](size_t a, size_t b) { return a + b; });
}

void ceiling(benchmark::State& state, const std::string& sceneName, bool occluded, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  const Scene& scene = benchScene(sceneName);
  const RaySet& set = raysFor(sceneName);
  auto rtcScene = static_cast<RTCScene>(scene.embreeHandle());
  size_t hits = 0, traced = 0;
  for (auto _ : state) {
    hits += traceAll(rtcScene, set, occluded);
    traced += kRays;
  }
  state.counters["rays_per_s"] = benchmark::Counter(static_cast<double>(traced), benchmark::Counter::kIsRate);
  state.counters["hit_fraction"] = traced ? static_cast<double>(hits) / static_cast<double>(traced) : 0.0;
  state.counters["threads"] = threads;
  state.counters["triangles"] = static_cast<double>(scene.triangleCount());
}

const bool registered = [] {
  std::vector<int> threadCounts = {1};
  if (allThreads() > 1) threadCounts.push_back(allThreads());
  for (const std::string& scene : bundledScenes())
    for (const bool occluded : {false, true})
      for (int threads : threadCounts)
        benchmark::RegisterBenchmark(
            fmt::format("Ceiling/{}/{}/threads:{}", scene, occluded ? "occluded" : "intersect", threads).c_str(),
            [=](benchmark::State& s) { ceiling(s, scene, occluded, threads); })
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

}  // namespace pathlab::bench
