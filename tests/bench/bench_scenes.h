// The bundled scenes the benchmarks run on, loaded once and shared by every benchmark.
#pragma once

#include "core/scene/scene.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace pathlab::bench {

// Stems of assets/*.gltf, sorted ("bidir-lamp", "caustic", "cornell-box", "veach-mis").
std::vector<std::string> bundledScenes();
// Loads assets/<name>.gltf on first use (benchmarks filtered out never load their scene).
const Scene& benchScene(const std::string& name);
// Every hardware thread (the "all threads" setting); at least 1.
int allThreads();

// A benchmark whose own check failed (its measurement would be wrong): skips it with `message`
// and makes pathlab_bench exit non-zero, so the CTest smoke run fails too (Google Benchmark's
// SkipWithError alone leaves the exit status 0).
void failBenchmark(benchmark::State& state, const std::string& message);
bool anyBenchmarkFailed();

}  // namespace pathlab::bench
