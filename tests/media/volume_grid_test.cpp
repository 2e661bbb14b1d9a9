// Heterogeneous media's building blocks (issue 35): the trilinear density field, the majorant
// grid that bounds it, and delta and ratio tracking against closed forms along a linear density
// ramp, where the optical depth is a quadratic in t.
#include "core/media/procedural_volumes.h"
#include "core/media/volume_grid.h"
#include "tests/support/chi2.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace pathlab {
namespace {

// The grids of makeProceduralVolume(.., n) placed in world space as `pathlab make-volume` places
// them: voxel size 1 / n, voxel centres filling the unit cube around the origin.
VolumeGrid unitCubeGrid(DensityGrid g, int n) {
  const Mat4 indexToWorld = glm::translate(Mat4(1.f), proceduralOrigin(n)) * glm::scale(Mat4(1.f), Vec3(proceduralVoxelSize(n)));
  return VolumeGrid(std::move(g), indexToWorld);
}

HomogeneousMedium greyMedium(float sigmaT, float albedo) {
  HomogeneousMedium m;
  m.sigmaT = Spectrum(sigmaT);
  m.sigmaS = Spectrum(albedo * sigmaT);
  return m;
}

TEST(DensityGrid, IsTrilinearBetweenVoxelCentresAndZeroOutside) {
  DensityGrid g;
  g.origin = glm::ivec3(2, 3, 4);
  g.size = glm::ivec3(2, 2, 2);
  g.values = {1, 2, 3, 4, 5, 6, 7, 8};
  EXPECT_FLOAT_EQ(g.lookup(Vec3(2, 3, 4)), 1.f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(3, 4, 5)), 8.f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(2.5f, 3.5f, 4.5f)), 4.5f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(2.25f, 3.f, 4.f)), 1.25f);
  // Half a voxel beyond the last sample the field fades toward the zero background.
  EXPECT_FLOAT_EQ(g.lookup(Vec3(3.5f, 3.f, 4.f)), 1.f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(4.f, 3.f, 4.f)), 0.f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(0.f, 0.f, 0.f)), 0.f);
  EXPECT_FLOAT_EQ(g.lookup(Vec3(std::nanf(""), 3.f, 4.f)), 0.f);
}

// Every point of every segment the majorant grid visits lies below that segment's majorant, and
// the segments tile the ray's overlap with the field's support without gaps.
TEST(MajorantGrid, BoundsTheFieldAlongEveryRay) {
  DensityGrid g;
  g.origin = glm::ivec3(-5, 0, 7);
  g.size = glm::ivec3(21, 13, 30);
  g.values.resize(g.voxelCount());
  Pcg32 rng(7, 3);
  for (float& v : g.values) v = rng.next1D() < 0.2f ? 5.f * rng.next1D() : 0.f;
  const MajorantGrid majorant(g);
  const Vec3 lo = Vec3(g.origin) - 1.f, hi = Vec3(g.origin + g.size);
  int checked = 0;
  // Random chords, axis-aligned rays (zero direction components, both signs) and rays starting on
  // a cell face (the lattice's corner is lo, cells 8 voxels a side).
  auto makeRay = [&](int ray, Vec3& a, Vec3& b) {
    a = lo - 4.f + (hi - lo + 8.f) * Vec3(rng.next1D(), rng.next1D(), rng.next1D());
    b = lo - 4.f + (hi - lo + 8.f) * Vec3(rng.next1D(), rng.next1D(), rng.next1D());
    if (ray % 4 == 1) {  // along one axis
      const int axis = ray / 4 % 3;
      for (int c = 0; c < 3; ++c)
        if (c != axis) b[c] = a[c];
    } else if (ray % 4 == 2) {  // from a cell face
      const int axis = ray / 4 % 3;
      a[axis] = lo[axis] + float(MajorantGrid::kCellVoxels * (ray / 12 % 4));
    }
  };
  for (int ray = 0; ray < 3000; ++ray) {
    Vec3 a, b;
    makeRay(ray, a, b);
    const float length = glm::length(b - a);
    if (!(length > 0.f)) continue;
    const Vec3 d = (b - a) / length;
    std::vector<std::pair<float, float>> visited;
    majorant.traverse(a, d, 0.f, length, [&](float t0, float t1, float m) {
      EXPECT_LT(t0, t1);
      if (!visited.empty()) {
        EXPECT_NEAR(t0, visited.back().second, 1e-4f * length);
      }
      visited.emplace_back(t0, t1);
      for (int i = 0; i < 8; ++i) {
        const float t = t0 + (t1 - t0) * rng.next1D();
        const float v = g.lookup(a + t * d);
        EXPECT_LE(v, m * (1.f + 1e-5f)) << "ray " << ray << " t " << t;
        ++checked;
      }
      return true;
    });
    // The field's support along the ray, by fine sampling: every non-zero sample lies in a
    // visited segment (a traversal that starts late or stops early fails here).
    for (int i = 0; i < 256; ++i) {
      const float t = length * (float(i) + 0.5f) / 256.f;
      if (!(g.lookup(a + t * d) > 0.f)) continue;
      const bool inside = std::any_of(visited.begin(), visited.end(), [&](const auto& s) {
        return t >= s.first - 1e-4f * length && t <= s.second + 1e-4f * length;
      });
      EXPECT_TRUE(inside) << "ray " << ray << ": density at t " << t << " outside every visited segment";
    }
  }
  EXPECT_GT(checked, 10000);
}

// The optical depth of the ramp's density x sigma along x(t) = o + t d inside the unit cube, where
// density = value (z + 1) exactly (makeProceduralVolume pads the faces): a quadratic in t.
double rampDepth(float value, float sigma, const Vec3& o, const Vec3& d, double t) {
  return double(sigma) * double(value) * ((double(o.z) + 1.0) * t + 0.5 * double(d.z) * t * t);
}

TEST(RatioTracking, IsUnbiasedAlongALinearRamp) {
  const int n = 16;
  const VolumeGrid grid = unitCubeGrid(makeProceduralVolume(ProceduralVolume::Ramp, n, 1.f), n);
  const HomogeneousMedium m = greyMedium(2.f, 0.5f);
  struct Case {
    Vec3 o, d;
    float tMax;
  };
  const Case cases[] = {{Vec3(0.f, 0.f, -0.49f), Vec3(0.f, 0.f, 1.f), 0.98f},
                        {Vec3(-0.4f, -0.3f, -0.45f), glm::normalize(Vec3(0.8f, 0.5f, 0.9f)), 1.1f},
                        {Vec3(0.3f, 0.2f, 0.45f), glm::normalize(Vec3(-0.6f, -0.2f, -0.9f)), 0.9f}};
  Pcg32 rng(11, 5);
  for (const Case& c : cases) {
    const double expected = std::exp(-rampDepth(1.f, 2.f, c.o, c.d, c.tMax));
    const int samples = 200000;
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < samples; ++i) {
      const double T = ratioTrack(m, grid, c.o, c.d, c.tMax, rng).r;
      sum += T;
      sum2 += T * T;
    }
    const double mean = sum / samples, se = std::sqrt((sum2 / samples - mean * mean) / samples);
    EXPECT_NEAR(mean, expected, 4.0 * se + 1e-6) << "expected " << expected << " se " << se;
    EXPECT_LT(se, 0.01 * expected);  // power: a 4 % bias would fail
  }
}

// Delta tracking's free-flight distances along the ramp: P(collision in [a, b)) =
// exp(-tau(a)) - exp(-tau(b)), and passing the segment exp(-tau(tMax)); Pearson's chi-square over
// 40 bins and the pass bin. In a white medium every weight is one.
TEST(DeltaTracking, FreeFlightDistancesFollowTheTransmittance) {
  const int n = 16;
  const VolumeGrid grid = unitCubeGrid(makeProceduralVolume(ProceduralVolume::Ramp, n, 1.f), n);
  const HomogeneousMedium m = greyMedium(3.f, 1.f);
  const Vec3 o(0.1f, -0.2f, -0.48f), d = glm::normalize(Vec3(0.1f, 0.3f, 1.f));
  const float tMax = 0.9f;
  const int bins = 40, samples = 200000;
  std::vector<double> counts(bins + 1, 0.0);
  Pcg32 rng(3, 9);
  for (int i = 0; i < samples; ++i) {
    const DistanceSample s = deltaTrack(m, grid, o, d, tMax, rng);
    ASSERT_NEAR(s.weight.r, 1.f, 1e-5f);
    counts[s.scattered ? std::min(bins - 1, int(s.t / tMax * bins)) : bins] += 1.0;
  }
  double chi2 = 0.0;
  for (int b = 0; b <= bins; ++b) {
    const double p = b < bins ? std::exp(-rampDepth(1.f, 3.f, o, d, tMax * b / bins)) -
                                    std::exp(-rampDepth(1.f, 3.f, o, d, tMax * (b + 1) / bins))
                              : std::exp(-rampDepth(1.f, 3.f, o, d, tMax));
    const double expected = p * samples;
    chi2 += (counts[size_t(b)] - expected) * (counts[size_t(b)] - expected) / expected;
  }
  const double pValue = test::regularizedGammaQ(0.5 * bins, 0.5 * chi2);
  EXPECT_GT(pValue, 1e-4) << "chi2 " << chi2 << " over " << bins << " degrees of freedom";
}

// Colour: the per-channel weights of spectral tracking. Passing the segment, delta tracking's
// expected weight is each channel's transmittance; and ratio tracking's estimate is unbiased per
// channel though the majorant is the largest channel's.
TEST(DeltaTracking, ChromaticExtinctionKeepsEachChannelsTransmittance) {
  const int n = 8;
  const VolumeGrid grid = unitCubeGrid(makeProceduralVolume(ProceduralVolume::Ramp, n, 1.f), n);
  HomogeneousMedium m;
  m.sigmaT = Spectrum(0.5f, 1.5f, 3.f);
  m.sigmaS = 0.7f * m.sigmaT;
  const Vec3 o(0.f, 0.f, -0.45f), d(0.f, 0.f, 1.f);
  const float tMax = 0.9f;
  const int samples = 400000;
  Pcg32 rng(5, 1);
  Spectrum passSum(0.f), passSum2(0.f), ratioSum(0.f), ratioSum2(0.f);
  for (int i = 0; i < samples; ++i) {
    const DistanceSample s = deltaTrack(m, grid, o, d, tMax, rng);
    const Spectrum pass = s.scattered ? Spectrum(0.f) : s.weight;
    passSum += pass;
    passSum2 += pass * pass;
    const Spectrum T = ratioTrack(m, grid, o, d, tMax, rng);
    ratioSum += T;
    ratioSum2 += T * T;
  }
  for (int c = 0; c < 3; ++c) {
    const double expected = std::exp(-rampDepth(1.f, m.sigmaT[c], o, d, tMax));
    for (const auto& [sum, sum2, what] : {std::tuple{passSum[c], passSum2[c], "delta"},
                                          std::tuple{ratioSum[c], ratioSum2[c], "ratio"}}) {
      const double mean = double(sum) / samples;
      const double se = std::sqrt(std::max(0.0, double(sum2) / samples - mean * mean) / samples);
      EXPECT_NEAR(mean, expected, 4.0 * se + 1e-6) << what << " channel " << c;
      EXPECT_LT(se, 0.02 * expected) << what << " channel " << c;
    }
  }
}

TEST(DensityGrid, PaddedConstantIsExactlyItsValueUpToTheCubesFaces) {
  // The grid the constant-versus-homogeneous renders read: one inside the whole unit cube, so
  // that its medium is the homogeneous one wherever the boundary mesh lets light in.
  const int n = 8;
  const VolumeGrid grid = unitCubeGrid(makeProceduralVolume(ProceduralVolume::Constant, n, 1.f), n);
  for (const Vec3 p : {Vec3(-0.5f), Vec3(0.f), Vec3(0.49f, -0.5f, 0.2f), Vec3(0.5f)})
    EXPECT_NEAR(grid.densityAt(p), 1.f, 1e-5f) << p.x << " " << p.y << " " << p.z;
  EXPECT_FLOAT_EQ(grid.densityAt(Vec3(0.5f + 1.5f / float(n), 0.f, 0.f)), 0.f);
}

}  // namespace
}  // namespace pathlab
