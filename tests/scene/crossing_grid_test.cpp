// The crossing grid counts the same crossings as testing every triangle: checked against grids of
// one triangle each on a soup of small and long thin triangles, and on a closed box's parity.
#include "core/scene/crossing_grid.h"

#include <gtest/gtest.h>

#include <random>

namespace pathlab {
namespace {

TEST(CrossingGrid, CountsTheCrossingsOfEveryTriangle) {
  std::mt19937 rng(37);
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
  std::vector<CrossingGrid::Triangle> soup;
  for (int i = 0; i < 400; ++i) {
    const Vec3 c = point();
    soup.push_back({c, c + 0.1f * point(), c + 0.1f * point()});
  }
  for (int i = 0; i < 40; ++i) soup.push_back({point(), point(), point()});  // spanning many cells
  std::vector<CrossingGrid> alone;
  for (const CrossingGrid::Triangle& t : soup) alone.emplace_back(std::vector<CrossingGrid::Triangle>{t});
  const CrossingGrid grid(soup);
  int total = 0;
  for (int k = 0; k < 3000; ++k) {
    const Vec3 p = 1.2f * point();
    int expected = 0;
    for (const CrossingGrid& g : alone) expected += g.crossings(p);
    ASSERT_EQ(grid.crossings(p), expected) << k;
    total += expected;
  }
  EXPECT_GT(total, 1000);  // the rays do cross triangles
}

TEST(CrossingGrid, ParityTellsInsideAClosedBox) {
  // The unit cube as 12 triangles.
  std::vector<CrossingGrid::Triangle> box;
  const Vec3 v[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int faces[6][4] = {{0, 1, 2, 3}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 2, 6, 7}, {0, 3, 7, 4}, {1, 2, 6, 5}};
  for (const auto& f : faces) {
    box.push_back({v[f[0]], v[f[1]], v[f[2]]});
    box.push_back({v[f[0]], v[f[2]], v[f[3]]});
  }
  const CrossingGrid grid(box);
  EXPECT_EQ(grid.crossings(Vec3(0.5f, 0.4f, 0.3f)) % 2, 1);
  EXPECT_EQ(grid.crossings(Vec3(0.9f, 0.1f, 0.8f)) % 2, 1);
  EXPECT_EQ(grid.crossings(Vec3(1.5f, 0.5f, 0.5f)) % 2, 0);
  EXPECT_EQ(grid.crossings(Vec3(-0.5f, 0.5f, 0.5f)) % 2, 0);
  EXPECT_EQ(CrossingGrid().crossings(Vec3(0.f)), 0);
}

}  // namespace
}  // namespace pathlab
