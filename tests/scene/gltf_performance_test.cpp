// The glTF loader's running time on a million triangles: a guard against quadratic steps.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

namespace pathlab {
namespace {

using namespace gltf_test;

TEST(GltfPerformance, AMillionTrianglesLoadInLinearTime) {
  // A 708 x 708 quad grid (1,002,528 triangles) in an external .bin. A quadratic step would take
  // hours; the bound is only a guard against that, the time is printed.
  const int n = 708;
  std::vector<Vec3> positions;
  positions.reserve(size_t(n + 1) * size_t(n + 1));
  for (int y = 0; y <= n; ++y) {
    for (int x = 0; x <= n; ++x) positions.emplace_back(float(x), float(y), 0.f);
  }
  std::vector<uint32_t> indices;
  indices.reserve(size_t(n) * size_t(n) * 6);
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const uint32_t a = uint32_t(y * (n + 1) + x), b = a + 1, c = a + uint32_t(n + 1), e = c + 1;
      for (uint32_t i : {a, b, e, a, e, c}) indices.push_back(i);
    }
  }
  TestGltf g;
  const int pos = g.vec3(positions);
  const int idx = g.indices(indices);
  g.root(R"({"mesh":)" + str(g.mesh({TestGltf::primitive(pos, idx)})) + "}");
  writeFile("million.bin", g.bin);
  const std::string json =
      replaced(g.json(), "data:application/octet-stream;base64," + base64(g.bin), "million.bin");
  const std::string path = writeFile("million.gltf", json);
  const auto start = std::chrono::steady_clock::now();
  const SceneDesc d = loadGltf(path);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(totalTriangles(d), size_t(n) * size_t(n) * 2);
  std::printf("[ INFO     ] %zu triangles loaded in %.2f s\n", totalTriangles(d), seconds);
  EXPECT_LT(seconds, 60.0);
  fs::remove(tempDir() / "million.bin");
  fs::remove(path);
}

}  // namespace
}  // namespace pathlab
