// The BPT's share of the ray-tracing ceiling for its own mix of rays (issue 11's definition): the
// rays one SmallVCM-scenario pass (Cornell box, 512², at most 10 edges, bpt, every technique)
// actually traces, recorded as they reach Embree (core/scene/ray_log.h) and traced again by raw
// rtcIntersect1 / rtcOccluded1 with nothing else around them (core/scene/ray_replay.h; every
// replayed answer must equal the logged one, or the benchmark stops with an error). Each
// iteration renders one pass (not recorded) and replays the recorded pass, both timed with the
// same threads, so share = (replay time per ray) / (render time per ray) compares the two in the
// same minute of a noisy machine. The replay keeps each thread's order
// (consecutive rays of one sample stay together, as their cache behaviour in the render has them)
// and hands the threads chunks of 1,024 consecutive rays.
#include "core/render/render_session.h"
#include "core/scene/ray_log.h"
#include "core/scene/ray_replay.h"
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>
#include <fmt/core.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>

namespace pathlab::bench {

namespace {

constexpr size_t kChunk = 1024;

struct Chunk {
  const LoggedRay* begin;
  size_t count;
};

// Traces every logged ray once, the chunks spread over the threads; returns how many answers
// differ from the logged ones (zero, or the replay is not of the render's work).
size_t replay(const Scene& scene, const std::vector<Chunk>& chunks) {
  std::atomic<size_t> mismatches{0};
  tbb::parallel_for(tbb::blocked_range<size_t>(0, chunks.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    size_t m = 0;
    for (size_t c = range.begin(); c < range.end(); ++c) m += replayRays(scene, chunks[c].begin, chunks[c].count);
    mismatches += m;
  });
  return mismatches.load();
}

void ownRays(benchmark::State& state, int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  const Scene& scene = benchScene("cornell-box");
  RenderSettings settings;
  settings.width = settings.height = 512;
  settings.maxLength = 10;
  settings.integrator = IntegratorKind::Bpt;
  RenderSession session(scene, settings);
  session.renderPass();  // warm: per-thread scratch, caches (as render_bench.cpp)

  RayLog log;
  scene.setRayLog(&log);
  const uint64_t before = session.counters().totalRays();
  session.renderPass();
  scene.setRayLog(nullptr);
  std::vector<Chunk> chunks;
  size_t logged = 0, shadow = 0;
  for (const std::vector<LoggedRay>* rays : log.streams()) {
    for (size_t i = 0; i < rays->size(); i += kChunk) chunks.push_back({rays->data() + i, std::min(kChunk, rays->size() - i)});
    logged += rays->size();
    for (const LoggedRay& r : *rays) shadow += r.occluded;
  }
  // The log must hold exactly the rays the counters say the pass traced, or the share is wrong.
  if (logged != session.counters().totalRays() - before) {
    failBenchmark(state, fmt::format("logged {} rays, the counters say {}", logged, session.counters().totalRays() - before));
    return;
  }
  using Clock = std::chrono::steady_clock;
  double renderSeconds = 0.0, replaySeconds = 0.0;
  uint64_t renderRays = 0, replayedRays = 0, samples = 0;
  size_t mismatches = 0;
  for (auto _ : state) {
    const Counters c0 = session.counters();
    const auto t0 = Clock::now();
    session.renderPass();
    const auto t1 = Clock::now();
    mismatches += replay(scene, chunks);
    const auto t2 = Clock::now();
    renderSeconds += std::chrono::duration<double>(t1 - t0).count();
    replaySeconds += std::chrono::duration<double>(t2 - t1).count();
    renderRays += session.counters().totalRays() - c0.totalRays();
    samples += session.counters().cameraSamples - c0.cameraSamples;
    replayedRays += logged;
    state.SetIterationTime(std::chrono::duration<double>(t2 - t0).count());
  }
  if (mismatches > 0) {
    failBenchmark(state, fmt::format("{} replayed rays got another answer than in the render", mismatches));
    return;
  }
  const double renderRate = renderSeconds > 0 ? static_cast<double>(renderRays) / renderSeconds : 0.0;
  const double replayRate = replaySeconds > 0 ? static_cast<double>(replayedRays) / replaySeconds : 0.0;
  state.counters["samples_per_s"] = renderSeconds > 0 ? static_cast<double>(samples) / renderSeconds : 0.0;
  state.counters["bpt_rays_per_s"] = renderRate;
  state.counters["ceiling_rays_per_s"] = replayRate;
  state.counters["share"] = replayRate > 0 ? renderRate / replayRate : 0.0;
  state.counters["shadow_ray_share"] = logged ? static_cast<double>(shadow) / static_cast<double>(logged) : 0.0;
  state.counters["rays_per_pass"] = static_cast<double>(logged);
  state.counters["threads"] = threads;
}

const bool registered = [] {
  std::vector<int> threadCounts = {1};
  if (allThreads() > 1) threadCounts.push_back(allThreads());
  for (int threads : threadCounts)
    benchmark::RegisterBenchmark(fmt::format("OwnRays/cornell-box/bpt/512/threads:{}", threads).c_str(),
                                 [=](benchmark::State& s) { ownRays(s, threads); })
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

}  // namespace pathlab::bench
