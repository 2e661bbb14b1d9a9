// Participating media (issue 16): the medium model against its closed forms, the phase function
// and distance sampling against their densities (chi-square), and every estimator against closed
// forms through media: transmittance through an absorbing slab, and a furnace filled with a
// scattering medium, for the path tracer, light tracing and BPT under each heuristic.
#include "core/media/medium.h"
#include "core/media/phase_function.h"
#include "core/render/render_session.h"
#include "core/sampling/warp.h"
#include "core/scene/media_step.h"
#include "core/scene/scene.h"
#include "tests/support/chi2.h"
#include "tests/support/image_means.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace pathlab {
namespace {

// --- The medium model ---------------------------------------------------------------------------

TEST(Medium, ExtinctionFromAttenuationColourAndDistance) {
  VolumeDesc v;
  v.attenuationColor = Spectrum(0.5f, 0.25f, 1.f);
  v.attenuationDistance = 2.f;
  const HomogeneousMedium m = HomogeneousMedium::fromVolume(v);
  // KHR_materials_volume: sigma_t = -ln(c) / d, and T(d) = c exactly.
  EXPECT_NEAR(m.sigmaT.r, std::log(2.0) / 2.0, 1e-6);
  EXPECT_NEAR(m.sigmaT.g, std::log(4.0) / 2.0, 1e-6);
  EXPECT_EQ(m.sigmaT.b, 0.f);
  EXPECT_FALSE(m.scatters());  // without KHR_materials_volume_scatter: absorption only
  const Spectrum T = m.transmittance(2.f);
  EXPECT_NEAR(T.r, 0.5f, 1e-6);
  EXPECT_NEAR(T.g, 0.25f, 1e-6);
  EXPECT_EQ(T.b, 1.f);
  // No attenuation distance: vacuum.
  EXPECT_TRUE(HomogeneousMedium::fromVolume(VolumeDesc{}).isVacuum());
}

TEST(Medium, SingleScatterAlbedoInvertsTheMultiscatterMapping) {
  // The draft's forward mapping: s^2 = (1 - a) / (1 - g a), multiscatter = (1 - s)(1 - 0.139 s) / (1 + 1.17 s).
  for (float g : {-0.5f, 0.f, 0.3f, 0.8f})
    for (float a : {0.f, 0.2f, 0.6f, 0.9f, 0.99f, 1.f}) {
      const float s = std::sqrt((1.f - a) / (1.f - g * a));
      const float ms = (1.f - s) * (1.f - 0.139f * s) / (1.f + 1.17f * s);
      EXPECT_NEAR(singleScatterAlbedo(Spectrum(ms), g).r, a, 2e-4) << "g " << g << " albedo " << a;
    }
  // White scatters without absorbing; the scattering coefficient is albedo x extinction.
  VolumeDesc v;
  v.attenuationColor = Spectrum(0.5f);
  v.attenuationDistance = 1.f;
  v.scatters = true;
  v.multiscatterColor = Spectrum(1.f);
  const HomogeneousMedium m = HomogeneousMedium::fromVolume(v);
  EXPECT_NEAR(m.sigmaS.g, m.sigmaT.g, 1e-6);
}

TEST(Medium, HenyeyGreensteinSamplingMatchesItsDensity) {
  const Vec3 wo = glm::normalize(Vec3(0.3f, -0.5f, 0.8f));
  const std::vector<float> gs = {-0.7f, 0.f, 0.4f, 0.9f};
  const double significance = test::sidakSignificance(0.01, static_cast<int>(gs.size()));
  for (const float g : gs) {
    const test::Chi2Result r = test::chi2SphereTest(
        [&](Pcg32& rng) -> std::optional<Vec3> { return samplePhaseHG(wo, g, rng.next2D()); },
        [&](const Vec3& wi) { return double(phaseHG(wo, wi, g)); }, 20, 40, 400000, 11, significance);
    EXPECT_TRUE(r.passed) << "g " << g << ": " << r.message;
  }
  // Forward scattering for g > 0: the mean cosine of the scattering angle is g.
  Pcg32 rng(5, 7);
  double meanCos = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) meanCos += -glm::dot(wo, samplePhaseHG(wo, 0.6f, rng.next2D()));
  EXPECT_NEAR(meanCos / n, 0.6, 0.01);
}

// Pearson's chi-square of sampleDistance's outcomes (bins over [0, tMax), and "passed") against
// distancePdf / passProbability, with chromatic extinction (the spectral MIS density).
TEST(Medium, DistanceSamplingMatchesItsDensity) {
  HomogeneousMedium m;
  m.sigmaT = Spectrum(0.5f, 2.f, 4.f);
  m.sigmaS = m.sigmaT * 0.8f;
  const float tMax = 1.5f;
  const int bins = 30, n = 300000;
  std::vector<double> observed(bins + 1, 0.0), expected(bins + 1, 0.0);
  Pcg32 rng(3, 9);
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next1D(), u = rng.next1D();
    const DistanceSample d = sampleDistance(m, tMax, uc, u);
    observed[d.scattered ? std::min(static_cast<int>(d.t / tMax * bins), bins - 1) : bins] += 1.0;
  }
  for (int b = 0; b < bins; ++b) {  // Simpson over each bin
    const float a = tMax * b / bins, c = tMax * (b + 1) / bins;
    expected[b] = n * (c - a) / 6.0 * (distancePdf(m, a) + 4.0 * distancePdf(m, 0.5f * (a + c)) + distancePdf(m, c));
  }
  expected[bins] = n * passProbability(m, tMax);
  double total = 0.0, chi2 = 0.0;
  for (int b = 0; b <= bins; ++b) {
    total += expected[b];
    chi2 += sqr(float(observed[b] - expected[b])) / expected[b];
  }
  EXPECT_NEAR(total, n, 1e-3 * n);  // the density and the pass probability account for everything
  const double p = test::regularizedGammaQ(bins / 2.0, chi2 / 2.0);  // bins + 1 cells, bins dof
  EXPECT_GT(p, 0.01) << "chi2 " << chi2;
  // The weights: E[weight] over the scatter events is the integral of sigma_s T, over the passes T(tMax).
  Spectrum scatterSum(0.f), passSum(0.f);
  for (int i = 0; i < n; ++i) {
    const float uc = rng.next1D(), u = rng.next1D();
    const DistanceSample d = sampleDistance(m, tMax, uc, u);
    (d.scattered ? scatterSum : passSum) += d.weight;
  }
  for (int c = 0; c < 3; ++c) {
    const double albedo = m.sigmaS[c] / m.sigmaT[c];
    EXPECT_NEAR(scatterSum[c] / n, albedo * (1.0 - std::exp(-m.sigmaT[c] * tMax)), 0.01) << c;
    EXPECT_NEAR(passSum[c] / n, std::exp(-m.sigmaT[c] * tMax), 0.01) << c;
  }
}

// --- Estimators through media ---------------------------------------------------------------------

RenderSettings settingsFor(IntegratorKind integrator, MisHeuristic h, int width, int maxLength, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = width;
  s.maxLength = maxLength;
  s.integrator = integrator;
  s.mis.heuristic = h;
  s.seed = seed;
  return s;
}

struct MediaCase {
  const char* name;
  IntegratorKind integrator;
  MisHeuristic heuristic;
  const char* techniques;  // nullptr: all
  std::optional<MediumSampling> medium = std::nullopt;  // unset: the integrator's default (pt: mis)
};
const MediaCase kMediaCases[] = {
    {"pt", IntegratorKind::Pt, MisHeuristic::Balance, nullptr},
    {"pt distance", IntegratorKind::Pt, MisHeuristic::Balance, nullptr, MediumSampling::Distance},
    {"pt equiangular", IntegratorKind::Pt, MisHeuristic::Balance, nullptr, MediumSampling::Equiangular},
    {"bpt balance", IntegratorKind::Bpt, MisHeuristic::Balance, nullptr},
    {"bpt power", IntegratorKind::Bpt, MisHeuristic::Power, nullptr},
    {"bpt uniform", IntegratorKind::Bpt, MisHeuristic::Uniform, nullptr},
    {"bpt subset", IntegratorKind::Bpt, MisHeuristic::Balance, "s=0;t=1;2,2;3,2"},
    {"lt", IntegratorKind::Bpt, MisHeuristic::Balance, "t=1"},
};

// An emitter (Le = 1) seen through a slab of purely absorbing medium of thickness d, bounded by
// an index-matched box: the radiance is exp(-sigma_t d) per channel (KHR_materials_volume's
// attenuation). The camera looks straight through it with a narrow field of view (yfov 0.01: the
// slant lengthens the path through the slab by at most 1.3e-5 of d, inside the slack below).
SceneDesc absorbingSlab(Spectrum sigmaT, float d) {
  SceneDesc desc;
  desc.path = "absorbing slab";
  desc.materials = {test::lambertian(0.f, Spectrum(1.f)), test::mediumBoundary(sigmaT, false)};
  desc.meshes = {test::quad(Vec3(-0.1f, -0.1f, -1.f), Vec3(0.1f, -0.1f, -1.f), Vec3(0.1f, 0.1f, -1.f),
                            Vec3(-0.1f, 0.1f, -1.f), 0)};  // faces +z, toward the camera
  for (TriangleMesh& m : test::outwardBox(Vec3(-0.5f, -0.5f, -0.6f), Vec3(0.5f, 0.5f, -0.6f + d), 1))
    desc.meshes.push_back(std::move(m));
  desc.camera = test::lookAt(Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, -1.f), Vec3(0, 1, 0), 0.01f);
  return desc;
}

TEST(MediaRender, AbsorbingSlabTransmitsExpMinusSigmaD) {
  const Spectrum sigmaT(0.3f, 1.f, 2.5f);
  const float d = 0.7f;
  const Scene scene(absorbingSlab(sigmaT, d));
  ASSERT_TRUE(scene.hasMedia());
  uint64_t seed = 1;
  for (const MediaCase& c : kMediaCases) {
    RenderSettings s = settingsFor(c.integrator, c.heuristic, 8, 4, seed++);
    if (c.techniques) s.techniques = TechniqueSet::parse(c.techniques);
    s.mediumSampling = c.medium;
    for (int channel = 0; channel < 3; ++channel) {
      const double expected = std::exp(-double(sigmaT[channel]) * d);
      const test::MeanEstimate m = test::passMeans(scene, s, 24, channel);
      EXPECT_LT(std::abs(m.mean - expected), test::kMaxZ * m.standardError + 1e-4 * expected)
          << c.name << " channel " << channel << ": mean " << m.mean << " expected " << expected << " se "
          << m.standardError;
    }
  }
}

// The furnace filled with a non-absorbing, forward-scattering medium: scattering moves light
// around without changing the answer, Le / (1 - rho) in every pixel (paths of up to 60 edges:
// the remainder is below rho^30 of the answer).
TEST(MediaRender, FoggyFurnaceKeepsLeOverOneMinusRho) {
  const float rho = 0.3f, Le = 0.7f;
  const Scene scene(test::foggyFurnace(rho, Le, 0.6f, 0.5f));
  ASSERT_TRUE(scene.hasMedia());
  ASSERT_EQ(scene.mediumAt(Vec3(0.1f, 0.2f, 0.3f)), 0);  // the camera is in the fog
  const double expected = Le / (1.0 - rho);
  uint64_t seed = 40;
  for (const MediaCase& c : kMediaCases) {
    RenderSettings s = settingsFor(c.integrator, c.heuristic, 8, 60, seed++);
    if (c.techniques) s.techniques = TechniqueSet::parse(c.techniques);
    s.mediumSampling = c.medium;
    // A subset without every technique of some length misses the paths only those sample: its
    // image is not the furnace's (light tracing alone samples every path here).
    if (c.techniques && std::string(c.techniques) != "t=1") continue;
    const test::MeanEstimate m = test::passMeans(scene, s, 256);
    EXPECT_LT(std::abs(m.zScore(expected)), test::kMaxZ)
        << c.name << ": mean " << m.mean << " expected " << expected << " se " << m.standardError;
    // Precise enough to see a bias of 20 %. Light tracing in a medium around a pinhole has infinite
    // variance (a point at distance r from the lens contributes ~1/r^2, and the volume near it
    // grows as r^2 dr), so where t = 1 carries weight the error falls slower than 1/sqrt(n).
    const bool heavyTail = c.heuristic == MisHeuristic::Uniform || (c.techniques && std::string(c.techniques) == "t=1");
    EXPECT_LT(m.standardError, (heavyTail ? 0.15 : 0.05) * expected) << c.name;
  }
}

// Every weighted path through the fog, medium vertices on either subpath and at the connection,
// has weights summing to one over its enabled techniques (misWeightSum), and the O(1) partial
// sums give the same image as the explicit weights.
TEST(MediaRender, WeightsArePartitionOfUnityWithMediumVertices) {
  const Scene scene(test::foggyFurnace(0.5f, 1.f, 1.f, 0.3f));
  for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
    RenderSettings s = settingsFor(IntegratorKind::Bpt, h, 12, 8, 3);
    s.checkMis = true;
    RenderSession session(scene, s);
    for (int i = 0; i < 4; ++i) session.renderPass();
    EXPECT_GT(session.counters().misPartitionChecks, 5000u);
    EXPECT_EQ(session.counters().misPartitionFailures, 0u) << misHeuristicName(h);
  }
}

// Camera, light and medium membership: volumes nest, the innermost wins, and a mesh's interface
// has the enclosing medium outside.
TEST(MediaScene, InnermostVolumeContainsThePoint) {
  SceneDesc desc = test::foggyFurnace(0.5f, 1.f, 0.5f, 0.f);
  desc.materials.push_back(test::mediumBoundary(Spectrum(3.f), false));  // material 2: an absorbing cube
  for (TriangleMesh& m : test::outwardBox(Vec3(-0.2f), Vec3(0.2f), 2)) desc.meshes.push_back(std::move(m));
  const Scene scene(std::move(desc));
  ASSERT_EQ(scene.media().media().size(), 2u);
  EXPECT_EQ(scene.mediumAt(Vec3(0.5f, 0.5f, 0.5f)), 0);  // fog
  EXPECT_EQ(scene.mediumAt(Vec3(0.f)), 1);               // the cube inside the fog
  EXPECT_EQ(scene.mediumAt(Vec3(5.f)), -1);              // outside everything
  // The cube's faces: the cube's medium inside, the fog outside; the fog box's: fog inside,
  // nothing outside; the walls (just outside the fog box): nothing on either side.
  const MediumInterface cube = scene.media().mesh(scene.meshes().size() - 1);
  EXPECT_EQ(cube.inside, 1);
  EXPECT_EQ(cube.outside, 0);
  EXPECT_EQ(scene.media().mesh(6).inside, 0);
  EXPECT_EQ(scene.media().mesh(6).outside, -1);
  EXPECT_EQ(scene.media().mesh(0).inside, -1);
  EXPECT_EQ(scene.media().mesh(0).outside, -1);
  EXPECT_TRUE(scene.media().indexMatched(scene.meshes().size() - 1));
  EXPECT_FALSE(scene.media().indexMatched(0));
}

TEST(MediaScene, ASceneWithoutMediaTracksNone) {
  const Scene scene(test::furnace(0.5f, 1.f));
  EXPECT_FALSE(scene.hasMedia());
  EXPECT_EQ(scene.mediumAt(Vec3(0.f)), -1);
  const std::optional<SurfaceHit> hit = scene.intersect(Ray{Vec3(0.f), Vec3(0.f, 0.f, 1.f)});
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->media.inside, -1);
  EXPECT_FALSE(hit->indexMatched);
}

// traceStep, the walks' one step. Without media: one ray cast, the hit Scene::intersect gives,
// the weight exactly one and no random number drawn (the images of every scene without media
// rest on all four). With media: traceThroughMedia's step, random numbers and ray count included.
TEST(MediaStep, WithoutMediaIsOneRayCastOfWeightOne) {
  const Scene scene(test::furnace(0.5f, 1.f));
  Pcg32 rng(7, 1), untouched(7, 1);
  Counters counters;
  const Ray up{Vec3(0.f), Vec3(0.f, 0.f, 1.f)};
  const MediaStep step = traceStep(scene, up, -1, rng, counters);
  EXPECT_EQ(step.kind, MediaStepKind::Surface);
  ASSERT_TRUE(step.hit);
  EXPECT_EQ(step.hit->t, scene.intersect(up)->t);
  EXPECT_EQ(step.hit->p, scene.intersect(up)->p);
  EXPECT_EQ(step.weight, Spectrum(1.f));
  EXPECT_EQ(counters.rays, 1u);
  EXPECT_EQ(rng.next1D(), untouched.next1D());
  const MediaStep away = traceStep(scene, Ray{Vec3(0.f, 0.f, 5.f), Vec3(0.f, 0.f, 1.f)}, -1, rng, counters);
  EXPECT_EQ(away.kind, MediaStepKind::Escaped);
  EXPECT_FALSE(away.hit);
  EXPECT_EQ(away.weight, Spectrum(1.f));
}

TEST(MediaStep, WithMediaIsTheMediaWalk) {
  const Scene scene(test::foggyFurnace(0.5f, 1.f, 1.f, 0.3f));
  ASSERT_TRUE(scene.hasMedia());
  Pcg32 directions(3, 5);
  int scattered = 0;
  for (uint64_t i = 0; i < 64; ++i) {
    const Ray ray{Vec3(0.1f, 0.2f, 0.3f), sampleUniformSphere(directions.next2D())};
    Pcg32 a(i, 2), b(i, 2);
    Counters ca, cb;
    const MediaStep s = traceStep(scene, ray, 0, a, ca);
    const MediaStep t = traceThroughMedia(scene, ray, 0, b, cb);
    EXPECT_EQ(s.kind, t.kind);
    EXPECT_EQ(s.weight, t.weight);
    EXPECT_EQ(s.p, t.p);
    EXPECT_EQ(s.hit.has_value(), t.hit.has_value());
    EXPECT_EQ(ca.rays, cb.rays);
    EXPECT_EQ(a.next1D(), b.next1D());
    scattered += s.kind == MediaStepKind::Medium;
  }
  EXPECT_GT(scattered, 0);
}

}  // namespace
}  // namespace pathlab
