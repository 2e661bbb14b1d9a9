// HashGrid: every point within r of a query found once, none outside, against brute force, on
// clustered and degenerate point sets; the same answer whatever the thread count that built it.
#include "core/merge/hash_grid.h"
#include "core/math/rng.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace pathlab {
namespace {

std::vector<uint32_t> bruteForceWithin(const std::vector<Vec3>& points, Vec3 x, float r) {
  std::vector<uint32_t> out;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3 d = points[i] - x;
    if (d.x * d.x + d.y * d.y + d.z * d.z <= r * r) out.push_back(static_cast<uint32_t>(i));
  }
  return out;
}

std::vector<uint32_t> gridFinds(const HashGrid& grid, Vec3 x) {
  std::vector<uint32_t> out;
  grid.query(x, [&](uint32_t i) { out.push_back(i); });
  std::sort(out.begin(), out.end());
  return out;
}

Vec3 uniformInBox(Pcg32& rng, Vec3 lo, Vec3 hi) { return lo + (hi - lo) * Vec3(rng.next1D(), rng.next1D(), rng.next1D()); }

TEST(HashGrid, FindsEveryPointWithinTheRadiusOnceAndNoneOutside) {
  Pcg32 rng(11, 3);
  // Clusters of light vertices (a lit floor, a caustic, walls) plus scattered ones, over a box
  // whose size is many radii.
  std::vector<Vec3> points;
  for (int i = 0; i < 3000; ++i) points.push_back(uniformInBox(rng, Vec3(-5.f), Vec3(5.f)));
  for (int i = 0; i < 3000; ++i) points.push_back(uniformInBox(rng, Vec3(1.f, 0.f, 1.f), Vec3(1.3f, 0.001f, 1.3f)));
  for (int i = 0; i < 500; ++i) points.push_back(Vec3(-2.f, 1.f, 0.5f));  // coincident
  size_t pairs = 0;
  for (const float r : {0.01f, 0.05f, 0.3f, 7.f}) {
    HashGrid grid;
    grid.build(points, r);
    ASSERT_EQ(grid.size(), points.size());
    for (int q = 0; q < 400; ++q) {
      // Queries near the points (where merges happen) and anywhere in and beyond the box.
      const Vec3 x = q % 2 ? points[rng.nextU32() % points.size()] + uniformInBox(rng, Vec3(-r), Vec3(r))
                           : uniformInBox(rng, Vec3(-7.f), Vec3(7.f));
      const std::vector<uint32_t> expected = bruteForceWithin(points, x, r), got = gridFinds(grid, x);
      ASSERT_EQ(got, expected) << "r " << r << " query " << q;
      pairs += got.size();
    }
  }
  EXPECT_GT(pairs, 10000u);  // the queries did find points
}

TEST(HashGrid, EmptyAndSinglePointGridsAndFarQueries) {
  HashGrid grid;
  grid.build({}, 0.1f);
  EXPECT_TRUE(gridFinds(grid, Vec3(0.f)).empty());
  const std::vector<Vec3> one{Vec3(1e6f, -1e6f, 3.f)};
  grid.build(one, 0.1f);
  EXPECT_EQ(gridFinds(grid, Vec3(1e6f, -1e6f, 3.05f)), (std::vector<uint32_t>{0}));
  EXPECT_TRUE(gridFinds(grid, Vec3(1e6f, -1e6f, 3.2f)).empty());
  EXPECT_TRUE(gridFinds(grid, Vec3(1e30f, 0.f, 0.f)).empty());  // clamped cell coordinates, no overflow
  EXPECT_THROW(grid.build(one, 0.f), std::invalid_argument);
  EXPECT_THROW(grid.build(one, std::numeric_limits<float>::infinity()), std::invalid_argument);
}

TEST(HashGrid, TheSameOrderWhateverTheThreadCount) {
  Pcg32 rng(4, 4);
  std::vector<Vec3> points;
  for (int i = 0; i < 200000; ++i) points.push_back(uniformInBox(rng, Vec3(-1.f), Vec3(1.f)));
  auto order = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    HashGrid grid;
    grid.build(points, 0.02f);
    std::vector<uint32_t> out;
    for (int q = 0; q < 200; ++q) grid.query(points[static_cast<size_t>(q) * 997], [&](uint32_t i) { out.push_back(i); });
    return out;
  };
  const std::vector<uint32_t> one = order(1);
  EXPECT_FALSE(one.empty());
  EXPECT_EQ(order(2), one);
  EXPECT_EQ(order(8), one);
}

}  // namespace
}  // namespace pathlab
