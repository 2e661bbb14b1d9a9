// The glTF loader's running time against the triangle count: a guard against steps quadratic in
// the triangles, kept here rather than in a timed unit test (these machines are shared and noisy;
// the brief keeps speed in benchmarks). Each size is an n x n quad grid (2 n² triangles) in an
// external .bin (emissive, so that the scene has a light), written once per run to a temporary folder; Google Benchmark fits the times to
// O(N) and prints the RMS of the fit, which stays small for a linear loader and grows for a
// quadratic one (docs/benchmarks.md, "glTF loading").
#include "core/scene/gltf_loader.h"
#include "tests/bench/bench_scenes.h"

#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <unistd.h>
#include <vector>

namespace pathlab::bench {

namespace {

namespace fs = std::filesystem;

size_t totalTriangles(const SceneDesc& desc) {
  size_t n = 0;
  for (const TriangleMesh& mesh : desc.meshes) n += mesh.triangleCount();
  return n;
}

fs::path gridFolder() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("pathlab_bench_gltf_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// The grid's .gltf: positions (float3) then indices (uint32) in one buffer.
std::string writeGrid(int n) {
  static std::map<int, std::string> written;
  if (auto it = written.find(n); it != written.end()) return it->second;
  std::vector<float> positions;
  positions.reserve(size_t(n + 1) * size_t(n + 1) * 3);
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) positions.insert(positions.end(), {float(x), float(y), 0.f});
  }
  std::vector<uint32_t> indices;
  indices.reserve(size_t(n) * size_t(n) * 6);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), e = c + 1;
      indices.insert(indices.end(), {a, b, e, a, e, c});
    }
  }
  const size_t positionBytes = positions.size() * sizeof(float), indexBytes = indices.size() * sizeof(uint32_t);
  const std::string stem = "grid-" + std::to_string(n);
  {
    std::ofstream bin(gridFolder() / (stem + ".bin"), std::ios::binary);
    bin.write(reinterpret_cast<const char*>(positions.data()), std::streamsize(positionBytes));
    bin.write(reinterpret_cast<const char*>(indices.data()), std::streamsize(indexBytes));
  }
  const std::string json = fmt::format(
      R"({{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],)"
      R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1,"material":0}}]}}],)"
      R"("materials":[{{"emissiveFactor":[1,1,1]}}],)"
      R"("buffers":[{{"uri":"{0}.bin","byteLength":{1}}}],)"
      R"("bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{2}}},{{"buffer":0,"byteOffset":{2},"byteLength":{3}}}],)"
      R"("accessors":[{{"bufferView":0,"componentType":5126,"count":{4},"type":"VEC3","min":[0,0,0],"max":[{5},{5},0]}},)"
      R"({{"bufferView":1,"componentType":5125,"count":{6},"type":"SCALAR"}}]}})",
      stem, positionBytes + indexBytes, positionBytes, indexBytes, (n + 1) * (n + 1), n, indices.size());
  const fs::path path = gridFolder() / (stem + ".gltf");
  std::ofstream(path) << json;
  return written[n] = path.string();
}

void gltfLoad(benchmark::State& state) {
  const int n = int(state.range(0));
  const std::string path = writeGrid(n);
  const size_t triangles = size_t(n) * size_t(n) * 2;
  for (auto _ : state) {
    SceneDesc desc;
    try {
      desc = loadGltf(path);
    } catch (const std::exception& e) {
      failBenchmark(state, e.what());
      return;
    }
    if (totalTriangles(desc) != triangles) {
      failBenchmark(state, fmt::format("{}: {} triangles loaded, {} expected", path, totalTriangles(desc), triangles));
      return;
    }
    benchmark::DoNotOptimize(desc);
  }
  state.SetComplexityN(int64_t(triangles));
  state.counters["triangles"] = double(triangles);
  state.counters["ns_per_triangle"] = benchmark::Counter(double(triangles), benchmark::Counter::kIsIterationInvariantRate |
                                                                                benchmark::Counter::kInvert);
}

// 62.7k to 4 M triangles, each size twice the last.
BENCHMARK(gltfLoad)
    ->Name("GltfLoad/grid")
    ->Arg(177)->Arg(250)->Arg(354)->Arg(500)->Arg(708)->Arg(1000)->Arg(1414)
    ->Unit(benchmark::kMillisecond)
    ->Complexity(benchmark::oN);

}  // namespace

}  // namespace pathlab::bench
