// Where the bidirectional walks start their Russian roulette (core/sampling/russian_roulette.h,
// RouletteCount): a camera walk does not count its delta bounces, so the first surface it sees
// by a non-delta scattering, through a mirror or glass, always gets its next bounce; a light walk
// counts every scattering, so its first non-delta scattering after a delta one is a decision.
// Shown in the delta furnace with nearly black walls (albedo 0.05): a decision there ends the
// walk 95 % of the time.
#include "core/bpt/subpath.h"
#include "core/camera/camera.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

constexpr int kMaxVertices = 8;

// Of the walks whose first non-delta surface vertex x_j comes after a delta bounce (j >= 2), the
// share that went on past it; `walks` counts them.
template <class Path, class Walk>
double continuedPastFirstNonDelta(Walk walk, int samples, int& walks) {
  Pcg32 rng(31, 7);
  Path path;
  int continued = 0;
  walks = 0;
  for (int i = 0; i < samples; ++i) {
    const int n = walk(rng, path);
    int j = 1;
    while (j < n && path[j].isDelta) ++j;
    if (j < 2 || j >= n || j + 1 >= kMaxVertices || path[j].type != VertexType::Surface) continue;
    ++walks;
    continued += n > j + 1 ? 1 : 0;
  }
  return walks > 0 ? static_cast<double>(continued) / walks : 0.0;
}

TEST(RouletteWalks, CameraWalkContinuesPastTheFirstSurfaceSeenInAMirror) {
  const Scene scene(test::deltaFurnace(0.05f, 1.f));
  const Camera camera(scene.cameraDesc(), 16, 12);
  Counters counters;
  int walks = 0;
  const double share = continuedPastFirstNonDelta<CameraSubpath>(
      [&](Pcg32& rng, CameraSubpath& path) {
        const Vec2 pRaster(rng.next1D() * 16.f, rng.next1D() * 12.f);
        return generateCameraSubpath(scene, camera, pRaster, rng.next2D(), rng, WalkOptions{kMaxVertices, true}, path,
                                     counters);
      },
      4000, walks);
  ASSERT_GT(walks, 200);
  // Only a failed BSDF sample (a grazing direction) may end it; counting the delta bounces, about
  // 5 % would go on.
  EXPECT_GT(share, 0.98) << walks << " walks";
}

TEST(RouletteWalks, LightWalkDecidesAtItsFirstNonDeltaScatteringAfterADeltaOne) {
  const Scene scene(test::deltaFurnace(0.05f, 1.f));
  Counters counters;
  int walks = 0;
  const double share = continuedPastFirstNonDelta<LightSubpath>(
      [&](Pcg32& rng, LightSubpath& path) {
        return generateLightSubpath(scene, rng, WalkOptions{kMaxVertices, true}, path, counters);
      },
      40000, walks);
  ASSERT_GT(walks, 200);
  // q = 0.05 at that decision: 0.05 with standard error sqrt(0.05 * 0.95 / walks) < 0.016.
  EXPECT_LT(share, 0.15) << walks << " walks";
}

}  // namespace
}  // namespace pathlab
