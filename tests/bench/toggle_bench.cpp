// Toggle latency: how long after a settings change the viewer's renderer publishes the first
// image of the new generation (the brief's "within 100 ms at 640x480"). A ProgressiveRenderer
// renders the Cornell box bidirectionally at 640x480 with all threads; each iteration switches
// one setting back and forth and times setSettings until a snapshot of the new generation exists
// (a coarse preview, as the viewer shows first).
#include "core/render/progressive_renderer.h"
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <chrono>
#include <functional>
#include <thread>

namespace pathlab::bench {

namespace {

using Change = std::function<void(RenderSettings&)>;

void toggleLatency(benchmark::State& state, const Change& change) {
  // The scene outlives the renderer: a shared_ptr that does not own it.
  const std::shared_ptr<const Scene> scene(&benchScene("cornell-box"), [](const Scene*) {});
  RenderSettings base;
  base.width = 640;
  base.height = 480;
  base.integrator = IntegratorKind::Bpt;
  RenderSettings changed = base;
  change(changed);
  ProgressiveRenderer renderer(scene, base);
  renderer.waitForSpp(2, 30.0);  // past the previews, as a user toggling mid-render
  bool toChanged = true;
  RenderSnapshot snapshot;
  double worst = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    renderer.setSettings(toChanged ? changed : base);
    const uint64_t generation = renderer.generation();
    while (!renderer.snapshot(snapshot) || snapshot.generation != generation)
      std::this_thread::sleep_for(std::chrono::microseconds(200));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    state.SetIterationTime(seconds);
    worst = std::max(worst, seconds);
    toChanged = !toChanged;
    // Let the new generation run a little, as between two clicks.
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  state.counters["worst_ms"] = worst * 1e3;
}

const bool registered = [] {
  const std::pair<const char*, Change> changes[] = {
      {"isolate", [](RenderSettings& s) { s.isolate = Isolation{1, 2, false}; }},
      {"heuristic", [](RenderSettings& s) { s.mis.heuristic = MisHeuristic::Power; }},
      {"max-length", [](RenderSettings& s) { s.maxLength = 5; }},
      {"integrator", [](RenderSettings& s) { s.integrator = IntegratorKind::Pt; }},
      {"techniques", [](RenderSettings& s) { s.techniques = TechniqueSet::parse("s=0;s=1;t=1"); }},
  };
  for (const auto& [name, change] : changes)
    benchmark::RegisterBenchmark(fmt::format("ToggleLatency/cornell-box/640x480/{}", name).c_str(),
                                 [change = change](benchmark::State& s) { toggleLatency(s, change); })
        ->UseManualTime()
        ->Iterations(20)
        ->Unit(benchmark::kMillisecond);
  return true;
}();

}  // namespace

}  // namespace pathlab::bench
