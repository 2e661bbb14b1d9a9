// Delta cases (Veach 1997, sec. 10.3.5): a point light (delta position), a smooth mirror and
// smooth glass (delta BSDFs) and the pinhole camera (delta position and direction). A connection
// (s, t) joins x(s-1) and x(s) deterministically, so it cannot reproduce a scattering that only a
// delta lobe can produce, and a delta-position endpoint cannot be hit by a ray. Hence:
//   - technique s = 0 is impossible when x0 is a point light;
//   - technique (s, t), s >= 1, is impossible when x(s-1) or x(s) scatters by a delta lobe;
//   - t = 1 through a pinhole is possible (x(n-1) is the camera, it only needs x(n-2) non-delta),
//     and so is (1, 1) for a point light in view (two delta positions joined by a visible edge).
// Each estimator is unbiased for the paths one of its techniques can sample, and the MIS weight
// of a path is normalised over the enabled techniques able to produce it (the impossible ones are
// left out of every weight), so the images of the estimators are predicted exactly:
//   PT (hits and next-event estimation): the paths whose x1 (first vertex after the light) is
//     non-delta, or whose x0 is on an area light;
//   LT (every (s, 1)): the paths whose x(n-2) (last vertex before the camera) is non-delta;
//   BPT with all techniques: the paths with at least one connectable edge, or an area-light x0.
// The tests compare the estimators on the pixel sets where these path sets coincide, check that
// they differ where they must, and check the impossible techniques give exactly nothing.
#include "core/render/render_session.h"
#include "tests/support/agreement.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace pathlab {
namespace {

using test::EstimatorSpec;
using test::PairSpec;
using test::PixelLabels;

using test::kFamilyAlpha;
constexpr int kDeltaSize = 24;

RenderSettings deltaSettings(int maxLength, IntegratorKind kind, MisHeuristic h, const std::string& techniques,
                            uint64_t seed) {
  RenderSettings s;
  s.width = s.height = kDeltaSize;
  s.maxLength = maxLength;
  s.integrator = kind;
  s.mis.heuristic = h;
  s.techniques = TechniqueSet::parse(techniques);
  s.seed = 1000 * test::testSeedBase() + seed;
  return s;
}

Image render(const Scene& scene, const RenderSettings& s, int passes) {
  RenderSession session(scene, s);
  for (int i = 0; i < passes; ++i) session.renderPass();
  return session.image();
}

// Largest |a - b| over the pixels and channels, relative to the largest |a|.
double relativeDifference(const Image& a, const Image& b) {
  double diff = 0.0, scale = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    diff = std::max(diff, std::abs(static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i])));
    scale = std::max(scale, std::abs(static_cast<double>(a.rgb[i])));
  }
  return scale > 0.0 ? diff / scale : diff;
}

double largestValue(const Image& a) {
  double m = 0.0;
  for (float v : a.rgb) m = std::max(m, std::abs(static_cast<double>(v)));
  return m;
}

// Label set 0: a 4 x 4 grid; 1: the grid without the pixels that see the mirror or the glass
// (dilated); 2: the pixels that see only the mirror or the glass (eroded), as 2 x 2 cells.
std::vector<PixelLabels> deltaLabels(const Scene& scene, const RenderSettings& s) {
  const PixelLabels grid = test::gridLabels(s.width, s.height, 4, 4);
  const PixelLabels clear = test::withoutSeenDirectly(scene, s, grid, test::hasDeltaLobe);
  const PixelLabels delta =
      test::onlySeenDirectly(scene, s, test::gridLabels(s.width, s.height, 2, 2), test::hasDeltaLobe);
  EXPECT_GT(test::labelledPixels(clear), s.width * s.height / 2);
  EXPECT_GT(test::labelledPixels(delta), 12);  // the test must look at the delta surfaces
  return {grid, clear, delta};
}

using test::report;

// Area light: every path that carries light has an area-light x0, which s = 0 can hit through
// any chain of delta scatterings, so PT and BPT (every heuristic) agree everywhere; LT agrees
// wherever the camera sees a non-delta surface, and is exactly black where it sees only the
// mirror or the glass (no t = 1 connection can end there).
TEST(DeltaAgreement, AreaLightMirrorGlassPinhole) {
  Scene scene(test::deltaScene(test::DeltaLight::Area));
  const int K = 5;
  const RenderSettings base = deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "all", 0);
  const auto labels = deltaLabels(scene, base);
  const std::vector<EstimatorSpec> estimators = {
      {"pt", deltaSettings(K, IntegratorKind::Pt, MisHeuristic::Balance, "all", 11), 384},
      {"balance", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "all", 12), 96},
      {"power", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Power, "all", 13), 96},
      {"uniform", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Uniform, "all", 14), 256},
      {"lt", deltaSettings(K, IntegratorKind::Lt, MisHeuristic::Balance, "all", 15), 128}};
  const auto run = test::runAgreement(scene, estimators, labels,
                                      {{"balance", "pt"},
                                       {"power", "pt"},
                                       {"uniform", "pt"},
                                       {"lt", "pt", 1},
                                       {"power", "balance"},
                                       {"uniform", "balance"},
                                       {"lt", "balance", 1}},
                                      kFamilyAlpha);
  report(run, "area light");
  test::expectAgreement(run, "area light, mirror, glass");

  // LT on the pixels that see only delta surfaces: exactly zero, not merely small.
  const test::RegionMeans& ltDelta = run.estimates[4 * labels.size() + 2];
  for (const auto& r : ltDelta.region)
    for (const auto& c : r) EXPECT_EQ(c.mean, 0.0);
  // ... while the other estimators see the mirror's and the sphere's images there.
  const test::RegionMeans& balanceDelta = run.estimates[1 * labels.size() + 2];
  EXPECT_GT(balanceDelta.whole[0].mean, 10.0 * balanceDelta.whole[0].standardError);
}

// Point light, maximum length 4. With "s=0;s=1" (the path tracer's techniques: hits and
// connections to the light) BPT samples the paths whose x1 is non-delta, as PT does: they agree
// everywhere. LT samples the paths whose x(n-2) is non-delta, as full BPT does on the pixels that
// see a non-delta surface (there x(n-2) is that surface): they agree there. On the pixels that
// see only the mirror or the glass, full BPT and PT sample the same paths up to 4 edges: with
// x(n-2) delta, the connectable edges are (x0, x1) and, for 4 edges, (x1, x2); both need x1
// non-delta, which is what PT needs (L S D D S E, the first path PT misses there, has 5 edges).
// So they agree there too. Where the mirror and the sphere
// send the point light onto the floor (L S D E, L S S D E: only t = 1 can sample them), full BPT
// must exceed PT by far more than the noise.
TEST(DeltaAgreement, PointLightMirrorGlassPinhole) {
  Scene scene(test::deltaScene(test::DeltaLight::Point));
  const int K = 4;
  const RenderSettings base = deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "all", 0);
  const auto labels = deltaLabels(scene, base);
  const std::vector<EstimatorSpec> estimators = {
      {"pt", deltaSettings(K, IntegratorKind::Pt, MisHeuristic::Balance, "all", 21), 256},
      {"balance s<=1", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "s=0;s=1", 22), 128},
      {"power s<=1", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Power, "s=0;s=1", 23), 128},
      {"uniform s<=1", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Uniform, "s=0;s=1", 24), 128},
      {"balance", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "all", 25), 96},
      {"power", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Power, "all", 26), 96},
      {"uniform", deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Uniform, "all", 27), 192},
      {"lt", deltaSettings(K, IntegratorKind::Lt, MisHeuristic::Balance, "all", 28), 256}};
  const auto run = test::runAgreement(scene, estimators, labels,
                                      {{"balance s<=1", "pt"},
                                       {"power s<=1", "pt"},
                                       {"uniform s<=1", "pt"},
                                       {"lt", "balance", 1},
                                       {"lt", "power", 1},
                                       {"lt", "uniform", 1, 0.08},
                                       {"power", "balance"},
                                       {"uniform", "balance", 0, 0.08},
                                       {"balance", "pt", 2},
                                       {"power", "pt", 2}},
                                      kFamilyAlpha);
  report(run, "point light");
  test::expectAgreement(run, "point light, mirror, glass");

  // The negative control: away from the delta surfaces full BPT sees the light the mirror and
  // the sphere throw on the floor, which PT cannot sample.
  const test::Agreement missed =
      test::compareRegions(run.estimates[4 * labels.size() + 1], run.estimates[0 * labels.size() + 1]);
  EXPECT_GT(missed.maxAbsZ, 3.0 * run.threshold) << missed.worst;
  std::cout << "full BPT vs PT away from the delta surfaces (must differ): " << missed.worst << "\n";
}

// With a point light no path can be hit (s = 0), so with "s=0;s=1" every path has exactly one
// enabled technique able to produce it, (1, t), whose weight is then 1 under every heuristic:
// the three images are the same numbers (the connection streams are keyed by sample and (s, t),
// bidir_tracer.cpp). Likewise "s=0;t=1" is light tracing exactly, and s = 0 alone is black.
TEST(DeltaAgreement, ImpossibleTechniquesContributeNothing) {
  Scene scene(test::deltaScene(test::DeltaLight::Point));
  const int K = 4, passes = 8;
  const Image balance =
      render(scene, deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Balance, "s=0;s=1", 5), passes);
  const Image power = render(scene, deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Power, "s=0;s=1", 5), passes);
  const Image uniform =
      render(scene, deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Uniform, "s=0;s=1", 5), passes);
  const Image s1 = render(scene, deltaSettings(K, IntegratorKind::Bpt, MisHeuristic::Uniform, "s=1", 5), passes);
  ASSERT_GT(largestValue(balance), 0.0);
  EXPECT_LT(relativeDifference(power, balance), 1e-5);
  EXPECT_LT(relativeDifference(uniform, balance), 1e-5);
  EXPECT_LT(relativeDifference(s1, balance), 1e-5);

  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
    const Image lt = render(scene, deltaSettings(K, IntegratorKind::Lt, h, "all", 6), passes);
    const Image s0t1 = render(scene, deltaSettings(K, IntegratorKind::Bpt, h, "s=0;t=1", 6), passes);
    ASSERT_GT(largestValue(lt), 0.0);
    EXPECT_LT(relativeDifference(s0t1, lt), 1e-5) << misHeuristicName(h);
    const Image s0 = render(scene, deltaSettings(K, IntegratorKind::Bpt, h, "s=0", 6), passes);
    EXPECT_EQ(largestValue(s0), 0.0) << misHeuristicName(h);
  }
}

// A point light seen by the pinhole camera: a path of one edge between two delta positions.
// s = 0 cannot hit the light, so (1, 1) is the only technique of length 1, and it is
// deterministic: every light subpath splats the same value at the light's raster position. That
// pixel measures the average over its film area of the radiance arriving at the pinhole; the
// light's radiance is a Dirac of weight E = I / d^2 in solid angle, and at distance 1 the film
// area per solid angle is 1 / cos^3(theta) (theta off the optical axis), so the pixel is
//   I / (d^2 cos^3(theta) A_pixel),   A_pixel = (2 tan(yfov/2))^2 (W/H) / (W H),
// every other pixel is black (Veach 1997, sec. 10.3.5; pbrt-v4 issue 347 for the splat scale).
// The path tracer cannot see it at all.
TEST(DeltaAgreement, PointLightSeenByThePinholeIsOnlyTheOneOneTechnique) {
  SceneDesc desc = test::floorScene(0.6f);
  PunctualLightDesc light;
  light.type = PunctualLightType::Point;
  light.intensity = 3.f;
  light.position = Vec3(0.f, 1.f, 0.f);
  desc.punctualLights = {light};
  const float yfov = 0.8f;
  const Vec3 eye(0.2f, 1.5f, 2.f), target(0.f, 0.5f, 0.f);
  desc.camera = test::lookAt(eye, target, Vec3(0, 1, 0), yfov);
  Scene scene(std::move(desc));
  const int W = 20, H = 16;
  auto settings = [&](IntegratorKind kind, const std::string& techniques, MisHeuristic h) {
    RenderSettings s;
    s.width = W;
    s.height = H;
    s.maxLength = 1;
    s.integrator = kind;
    s.techniques = TechniqueSet::parse(techniques);
    s.mis.heuristic = h;
    s.seed = 9;
    return s;
  };
  const Camera camera(scene.cameraDesc(), W, H);
  const auto raster = camera.rasterPosition(light.position);
  ASSERT_TRUE(raster.has_value());
  const int px = static_cast<int>(raster->x), py = static_cast<int>(raster->y);
  const Vec3 toLight = light.position - eye;
  const double d2 = glm::dot(toLight, toLight);
  const double cosTheta = glm::dot(glm::normalize(toLight), glm::normalize(target - eye));
  const double tanHalfY = std::tan(0.5 * yfov), tanHalfX = tanHalfY * W / H;
  const double aPixel = 4.0 * tanHalfX * tanHalfY / (W * H);
  const double expected = light.intensity / (d2 * cosTheta * cosTheta * cosTheta * aPixel);

  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
    const Image oneOne = render(scene, settings(IntegratorKind::Bpt, "1,1", h), 4);
    const Image lengthOne = render(scene, settings(IntegratorKind::Bpt, "k=1", h), 4);
    const Image lt = render(scene, settings(IntegratorKind::Lt, "all", h), 4);
    for (int y = 0; y < H; ++y)
      for (int x = 0; x < W; ++x) {
        const Vec3 v = oneOne.at(x, y);
        if (x == px && y == py)
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(v[c], expected, 1e-4 * expected) << misHeuristicName(h);
        else
          EXPECT_EQ(v, Vec3(0.f)) << x << "," << y;
      }
    EXPECT_LT(relativeDifference(lengthOne, oneOne), 1e-6) << misHeuristicName(h);
    EXPECT_LT(relativeDifference(lt, oneOne), 1e-6) << misHeuristicName(h);
    EXPECT_EQ(largestValue(render(scene, settings(IntegratorKind::Bpt, "0,2", h), 4)), 0.0);
  }
  EXPECT_EQ(largestValue(render(scene, settings(IntegratorKind::Pt, "all", MisHeuristic::Balance), 4)), 0.0);
}

}  // namespace
}  // namespace pathlab
