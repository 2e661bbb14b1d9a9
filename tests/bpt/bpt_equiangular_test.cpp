// The bidirectional equiangular technique E(1, k) (core/bpt/equiangular_technique.h, issue 35).
#include "core/bpt/connect.h"
#include "core/bpt/equiangular_technique.h"
#include "core/bpt/mis.h"
#include "core/bpt/subpath.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

Scene fogLamp() { return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/fog-lamp.gltf")); }

struct Mean {
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  void add(double x) { sum += x, sum2 += x * x, ++n; }
  double mean() const { return sum / n; }
  double standardError() const { return std::sqrt(std::max(sum2 / n - mean() * mean(), 0.0) / n); }
};

// Single scattering along one camera ray: E(1, 2)'s unweighted estimate (a vertex placed toward
// the light point) and C(1, 2)'s (a vertex placed by distance sampling, next-event estimation from
// it) estimate the same integral, the light scattered once into the ray.
TEST(BptEquiangular, UnweightedEstimateOfSingleScatteringIsDistanceSamplings) {
  const Scene scene = fogLamp();
  ASSERT_TRUE(hasEquiangularMedium(scene));
  const Camera camera(scene.cameraDesc(), 64, 48);
  Counters counters;
  for (const Vec2 pixel : {Vec2(36.5f, 16.5f), Vec2(20.5f, 30.5f), Vec2(50.5f, 40.5f)}) {
    Mean distance, equiangular;
    Pcg32 rng(77, static_cast<uint64_t>(pixel.x));
    CameraSubpath cp;
    LightSubpath lp;  // unused by s = 1
    const WalkOptions walk{2, false, scene.mediumAt(camera.position()), true};
    for (int i = 0; i < 200000; ++i) {
      const int nt = generateCameraSubpath(scene, camera, pixel, Vec2(0.5f), rng, walk, cp, counters);
      ASSERT_EQ(cp.rayCount, 1);
      double a = 0.0;
      if (nt == 2 && cp[1].type == VertexType::Medium) {
        const Connection c = connect(scene, camera, lp, 1, cp, 2, rng, counters);
        a = luminance(c.L);
      }
      distance.add(a);
      PathVertex x;
      Connection c;
      double b = 0.0;
      if (formEquiangularConnection(scene, cp, 2, rng, x, c, counters))
        b = luminance(c.L * transmittance(scene, c.shadowRay));
      equiangular.add(b);
    }
    const double se = std::hypot(distance.standardError(), equiangular.standardError());
    EXPECT_NEAR(equiangular.mean(), distance.mean(), 4.0 * se)
        << "pixel " << pixel.x << "," << pixel.y << " (standard errors " << distance.standardError() << ", "
        << equiangular.standardError() << ")";
  }
}

// A camera walk that ends before shooting a ray (a film position the camera gives no importance)
// leaves no recorded ray behind from the buffer's previous walk: E would read it.
TEST(BptEquiangular, AWalkWithoutARayRecordsNone) {
  const Scene scene = fogLamp();
  const Camera camera(scene.cameraDesc(), 64, 48);
  Counters counters;
  Pcg32 rng(3, 4);
  CameraSubpath cp;
  const WalkOptions walk{4, false, scene.mediumAt(camera.position()), true};
  generateCameraSubpath(scene, camera, Vec2(30.5f, 20.5f), Vec2(0.5f), rng, walk, cp, counters);
  ASSERT_GE(cp.rayCount, 1);
  EXPECT_EQ(generateCameraSubpath(scene, camera, Vec2(-40.f, -40.f), Vec2(0.5f), rng, walk, cp, counters), 1);
  EXPECT_EQ(cp.rayCount, 0);
  PathVertex x;
  Connection c;
  EXPECT_FALSE(formEquiangularConnection(scene, cp, 2, rng, x, c, counters));
}

}  // namespace
}  // namespace pathlab
