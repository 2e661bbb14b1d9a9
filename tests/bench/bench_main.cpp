// pathlab_bench's entry point: Google Benchmark's main, with the machine's load average printed
// before and after, because these machines are shared and every figure must be read beside it.
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace {

std::string loadAverage() {
  std::ifstream in("/proc/loadavg");
  std::string one, five, fifteen;
  in >> one >> five >> fifteen;
  return one + " " + five + " " + fifteen;
}

}  // namespace

int main(int argc, char** argv) {
  std::fprintf(stderr, "pathlab_bench: load average (1, 5, 15 min) before: %s\n", loadAverage().c_str());
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  const size_t ran = benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::fprintf(stderr, "pathlab_bench: load average (1, 5, 15 min) after: %s\n", loadAverage().c_str());
  // A filter that matches nothing is an error, so the CTest smoke run notices renamed benchmarks;
  // so is a benchmark whose own check failed (failBenchmark).
  if (pathlab::bench::anyBenchmarkFailed()) {
    std::fprintf(stderr, "pathlab_bench: a benchmark failed its own check (see its error above)\n");
    return 1;
  }
  return ran > 0 ? 0 : 1;
}
