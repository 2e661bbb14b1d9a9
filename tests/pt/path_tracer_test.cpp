// Closed forms rendered by the path tracer: the white furnace, direct lighting of a Lambertian
// floor by a square emitter (form factor), and by point, spot and directional lights.
// Every comparison is a z-test against the measured standard error with a fixed seed.
#include "core/render/render_session.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace pathlab {
namespace {

using test::floorScene;
using test::furnace;
using test::lambertian;
using test::MeanEstimate;
using test::quad;
using test::RunningStats;

using test::kMaxZ;

// Averages `passes` camera samples of every pixel's estimate (luminance of channel 0 here: the
// scenes are grey) through RenderSession::replaySample, the same code path as a render pass.
MeanEstimate renderMean(const Scene& scene, const RenderSettings& s, int passes,
                        const std::function<double(int, int)>& expected = {}, MeanEstimate* expectedMean = nullptr) {
  RenderSession session(scene, s);
  RunningStats stats, expectedStats;
  Counters counters;
  for (int pass = 0; pass < passes; ++pass)
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x) {
        const Spectrum L = session.replaySample(x, y, static_cast<uint64_t>(pass), counters);
        EXPECT_TRUE(isValidContribution(L));
        stats.add(L.r);
        if (expected && pass == 0) expectedStats.add(expected(x, y));
      }
  if (expectedMean) *expectedMean = expectedStats.estimate();
  return stats.estimate();
}


struct FurnaceCase {
  float rho;
  int maxLength;
  bool rr;
};

class PathTracerFurnace : public ::testing::TestWithParam<FurnaceCase> {};

// Closed box, every wall albedo rho and emission Le: every pixel sees
// Le (1 + rho + ... + rho^(K-1)) = Le (1 - rho^K) / (1 - rho) at maximum length K.
TEST_P(PathTracerFurnace, MatchesGeometricSeries) {
  const FurnaceCase c = GetParam();
  const float Le = 0.7f;
  Scene scene(furnace(c.rho, Le));
  RenderSettings s;
  s.width = s.height = 16;
  s.maxLength = c.maxLength;
  s.russianRoulette = c.rr;
  s.seed = 17;
  const MeanEstimate m = renderMean(scene, s, 24);
  const double expected = Le * (1.0 - std::pow(c.rho, c.maxLength)) / (1.0 - c.rho);
  if (m.standardError == 0.0) {
    EXPECT_NEAR(m.mean, expected, 1e-5 * expected);
  } else {
    EXPECT_LT(std::abs(m.zScore(expected)), kMaxZ) << "mean " << m.mean << " expected " << expected << " se " << m.standardError;
    EXPECT_LT(m.standardError, 0.02 * expected);  // the test has power to see a 10% bias
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, PathTracerFurnace,
                         ::testing::Values(FurnaceCase{0.5f, 1, false}, FurnaceCase{0.5f, 2, false},
                                           FurnaceCase{0.5f, 5, false}, FurnaceCase{0.8f, 20, true},
                                           FurnaceCase{0.8f, 20, false}, FurnaceCase{0.95f, 60, true}),
                         [](const auto& info) {
                           return "rho" + std::to_string(static_cast<int>(info.param.rho * 100)) + "_K" +
                                  std::to_string(info.param.maxLength) + (info.param.rr ? "_rr" : "");
                         });

// Form factor from a differential area to a parallel rectangle [0,a] x [0,b] at height h whose
// corner lies straight above it (Howell's catalogue, C-11), extended as an odd function of a and
// b so any rectangle is a signed sum of four corner rectangles.
double cornerFormFactor(double a, double b, double h) {
  const double A = std::abs(a) / h, B = std::abs(b) / h;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  const double f = (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2 * M_PI);
  return (a < 0) != (b < 0) ? -f : f;
}

double rectangleFormFactor(double x0, double x1, double z0, double z1, double h) {
  return cornerFormFactor(x1, z1, h) - cornerFormFactor(x0, z1, h) - cornerFormFactor(x1, z0, h) +
         cornerFormFactor(x0, z0, h);
}

// The floor point a pixel centre sees (the film footprint of a pixel is tiny in these tests).
Vec3 floorPointOfPixel(const Camera& camera, int x, int y) {
  const Ray r = camera.generateRay(Vec2(x + 0.5f, y + 0.5f), Vec2(0.5f));
  return r.o + r.d * (-r.o.y / r.d.y);
}


// Radiance reflected by a Lambertian floor under a square emitter of radiance Le:
// Lo = rho / pi * E = rho * Le * F (the form factor of the emitter from the floor point).
TEST(PathTracerDirect, SquareEmitterFormFactor) {
  const float rho = 0.5f, Le = 1.f, side = 1.f, h = 1.f;
  SceneDesc desc = floorScene(rho);
  Material emitter = lambertian(0.f, Spectrum(Le));
  desc.materials.push_back(emitter);
  const float s = side / 2;
  desc.meshes.push_back(quad(Vec3(-s, h, -s), Vec3(s, h, -s), Vec3(s, h, s), Vec3(-s, h, s), 1));  // faces -y
  desc.camera = test::lookAt(Vec3(0.3f, 0.5f, 0.6f), Vec3(0.35f, 0.f, 0.f), Vec3(0, 1, 0), 0.05f);
  Scene scene(std::move(desc));
  RenderSettings settings;
  settings.width = settings.height = 8;
  settings.maxLength = 2;
  settings.seed = 3;
  const Camera camera(scene.cameraDesc(), settings.width, settings.height);
  MeanEstimate expected;
  const MeanEstimate m = renderMean(
      scene, settings, 256,
      [&](int x, int y) {
        const Vec3 p = floorPointOfPixel(camera, x, y);
        return rho * Le * rectangleFormFactor(-s - p.x, s - p.x, -s - p.z, s - p.z, h);
      },
      &expected);
  EXPECT_LT(std::abs(m.zScore(expected.mean)), kMaxZ) << "mean " << m.mean << " expected " << expected.mean;
  EXPECT_LT(m.standardError, 0.01 * expected.mean);
}

struct PunctualCase {
  PunctualLightType type;
  Vec3 lookAt;
  const char* name;
};

class PathTracerPunctual : public ::testing::TestWithParam<PunctualCase> {};

// Point and spot: Lo = rho / pi * I * cos(theta) / d^2 (times the spot's falloff, here 1 inside
// the inner cone and 0 outside the outer one); directional: Lo = rho / pi * E * cos(theta).
TEST_P(PathTracerPunctual, MatchesInverseSquareLaw) {
  const PunctualCase c = GetParam();
  const float rho = 0.6f, I = 3.f;
  const Vec3 lightPos(0.f, 1.f, 0.f);
  const Vec3 dirTravel = glm::normalize(Vec3(1.f, -1.f, 0.f));
  SceneDesc desc = floorScene(rho);
  PunctualLightDesc light;
  light.type = c.type;
  light.intensity = I;
  light.position = lightPos;
  light.direction = c.type == PunctualLightType::Directional ? dirTravel : Vec3(0, -1, 0);
  light.innerConeAngle = 0.5f;
  light.outerConeAngle = 0.6f;
  desc.punctualLights = {light};
  desc.camera = test::lookAt(c.lookAt + Vec3(0.f, 0.5f, 0.4f), c.lookAt, Vec3(0, 1, 0), 0.05f);
  Scene scene(std::move(desc));
  RenderSettings settings;
  settings.width = settings.height = 8;
  settings.maxLength = 2;
  const Camera camera(scene.cameraDesc(), settings.width, settings.height);
  MeanEstimate expected;
  const MeanEstimate m = renderMean(
      scene, settings, 4,
      [&](int x, int y) -> double {
        const Vec3 p = floorPointOfPixel(camera, x, y);
        if (c.type == PunctualLightType::Directional) return rho / M_PI * I * -dirTravel.y;
        const Vec3 d = lightPos - p;
        const double cosTheta = d.y / glm::length(d);  // at the floor, and from the spot's axis -y
        if (c.type == PunctualLightType::Spot && cosTheta < std::cos(0.6)) return 0.0;
        return rho / M_PI * I * cosTheta / glm::dot(d, d);
      },
      &expected);
  // Direct lighting from a delta light has no variance beyond the pixel footprint: compare to the
  // closed form with the spread of that footprint as the tolerance.
  EXPECT_NEAR(m.mean, expected.mean, 1e-3 * expected.mean + 4 * m.standardError) << c.name;
  if (c.type == PunctualLightType::Spot && c.lookAt.x > 1.f) {
    EXPECT_EQ(m.mean, 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(Lights, PathTracerPunctual,
                         ::testing::Values(PunctualCase{PunctualLightType::Point, Vec3(0.4f, 0, 0.1f), "point"},
                                           PunctualCase{PunctualLightType::Spot, Vec3(0.2f, 0, 0.1f), "spot-inside"},
                                           PunctualCase{PunctualLightType::Spot, Vec3(1.5f, 0, 0.f), "spot-outside"},
                                           PunctualCase{PunctualLightType::Directional, Vec3(0.f), "directional"}),
                         [](const auto& info) {
                           std::string n = info.param.name;
                           std::replace(n.begin(), n.end(), '-', '_');
                           return n;
                         });

}  // namespace
}  // namespace pathlab
