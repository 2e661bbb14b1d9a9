// Throughput of the integrators: camera samples/s and rays/s of bpt, pt and lt on every bundled
// scene, one RenderSession pass per iteration, at 1 thread and at all threads; and the SmallVCM
// comparison scenario (the all-diffuse Cornell box, 512², at most 10 path segments, bpt).
#include "core/render/render_session.h"
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>
#include <fmt/core.h>
#include <tbb/global_control.h>

namespace pathlab::bench {

namespace {

constexpr int kSide = 128;  // small: a pass takes a fraction of a second on every scene
constexpr int kMaxLength = 10;

// imageOnlyPath false: the BPT evaluates every technique through its general path
// (BidirTracer::setImageOnlyPath), to measure what the image-only path saves.
// techniques: a --techniques SPEC for the bidirectional tracer ("all;m=all" is vcm), or empty for
// the integrator's own.
void renderPasses(benchmark::State& state, const std::string& sceneName, IntegratorKind integrator, int side,
                  int threads, bool imageOnlyPath = true, const std::string& techniques = "") {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  const Scene& scene = benchScene(sceneName);
  RenderSettings settings;
  settings.width = settings.height = side;
  settings.maxLength = kMaxLength;
  settings.integrator = integrator;
  if (!techniques.empty()) settings.techniques = TechniqueSet::parse(techniques);
  RenderSession session(scene, settings);
  session.setImageOnlyPath(imageOnlyPath);
  // One untimed pass first: the first pass of a session also pays for per-thread scratch and
  // cold caches, which a progressive render amortises over hundreds of passes.
  session.renderPass();
  const Counters warm = session.counters();
  for (auto _ : state) session.renderPass();
  const Counters& c = session.counters();
  const auto samples = static_cast<double>(c.cameraSamples - warm.cameraSamples);
  const auto rays = static_cast<double>(c.totalRays() - warm.totalRays());
  const auto shadowRays = static_cast<double>(c.shadowRays - warm.shadowRays);
  // kIsRate divides by the benchmark's time, which is wall time (UseRealTime below): the work
  // runs on TBB worker threads, so the main thread's CPU time would overstate the rate.
  state.counters["samples_per_s"] = benchmark::Counter(samples, benchmark::Counter::kIsRate);
  state.counters["rays_per_s"] = benchmark::Counter(rays, benchmark::Counter::kIsRate);
  state.counters["shadow_ray_share"] = rays > 0 ? shadowRays / rays : 0.0;
  state.counters["rays_per_sample"] = samples > 0 ? rays / samples : 0.0;
  state.counters["threads"] = threads;
}

const bool registered = [] {
  const std::pair<IntegratorKind, const char*> integrators[] = {
      {IntegratorKind::Bpt, "bpt"}, {IntegratorKind::Pt, "pt"}, {IntegratorKind::Lt, "lt"}};
  std::vector<int> threadCounts = {1};
  if (allThreads() > 1) threadCounts.push_back(allThreads());
  for (const std::string& scene : bundledScenes())
    for (const auto& [kind, name] : integrators)
      for (int threads : threadCounts)
        benchmark::RegisterBenchmark(fmt::format("Render/{}/{}/threads:{}", scene, name, threads).c_str(),
                                     [=](benchmark::State& s) { renderPasses(s, scene, kind, kSide, threads); })
            ->UseRealTime()
            ->Unit(benchmark::kMillisecond);
  // SmallVCM's comparison scenario (its README reports samples/s of its BPT on this scene).
  for (int threads : threadCounts)
    benchmark::RegisterBenchmark(fmt::format("SmallVCM/cornell-box/bpt/512/threads:{}", threads).c_str(),
                                 [=](benchmark::State& s) {
                                   renderPasses(s, "cornell-box", IntegratorKind::Bpt, 512, threads);
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  // The same through the general path alone: the image-only path's saving, measured in one run.
  for (int threads : threadCounts)
    benchmark::RegisterBenchmark(fmt::format("SmallVCMGeneralPath/cornell-box/bpt/512/threads:{}", threads).c_str(),
                                 [=](benchmark::State& s) {
                                   renderPasses(s, "cornell-box", IntegratorKind::Bpt, 512, threads, false);
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  // Vertex connection and merging on the same scenario: issue 32's anchor is SmallVCM's VCM there
  // (its 0.10 M camera samples/s), and its target VCM at most 25 % below pathlab's own BPT.
  for (int threads : threadCounts)
    benchmark::RegisterBenchmark(fmt::format("SmallVCM/cornell-box/vcm/512/threads:{}", threads).c_str(),
                                 [=](benchmark::State& s) {
                                   renderPasses(s, "cornell-box", IntegratorKind::Bpt, 512, threads, true, "all;m=all");
                                 })
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

}  // namespace pathlab::bench
