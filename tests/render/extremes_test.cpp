// Numerical extremes (issue 6): albedo near one with paths of up to 1000 edges, where throughput
// and density products over hundreds of vertices must neither overflow nor underflow, and
// Russian roulette must still reach the lengths that carry the answer.
#include "core/render/render_session.h"
#include "tests/support/image_means.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

// Every pixel of the furnace sees Le (1 - rho^K) / (1 - rho) at maximum length K; per-pass
// image means (every pixel is one sample of the same value) give the standard error.
TEST(Extremes, AlbedoNearOneWithThousandEdgePaths) {
  const float rho = 0.999f, Le = 0.01f;
  const int K = 1000;
  const double expected = Le * (1.0 - std::pow(static_cast<double>(rho), K)) / (1.0 - rho);
  const Scene scene(test::furnace(rho, Le));
  struct Case {
    IntegratorKind integrator;
    const char* techniques;
    MisHeuristic heuristic;
  };
  // The full BPT connects every prefix pair: O(n^2) connections with O(n) weights each, about 1e9
  // operations a sample at n = 1000. The linear-cost subsets exercise the same long subpaths
  // and weights over 1000 vertices: path tracing with next-event estimation and light tracing.
  for (const Case& c : {Case{IntegratorKind::Pt, "all", MisHeuristic::Balance},
                        Case{IntegratorKind::Bpt, "s=0;s=1;t=1", MisHeuristic::Balance},
                        Case{IntegratorKind::Bpt, "s=0;s=1;t=1", MisHeuristic::Power},
                        Case{IntegratorKind::Bpt, "s=0;s=1", MisHeuristic::Uniform},
                        Case{IntegratorKind::Lt, "all", MisHeuristic::Balance}}) {
    RenderSettings s;
    s.width = s.height = 2;
    s.maxLength = K;
    s.seed = 77;
    s.integrator = c.integrator;
    s.techniques = TechniqueSet::parse(c.techniques);
    s.mis.heuristic = c.heuristic;
    s.checkMis = c.integrator != IntegratorKind::Pt;
    const test::MeanEstimate m = test::passMeans(scene, s, 24);
    SCOPED_TRACE(testing::Message() << integratorName(c.integrator) << " " << c.techniques << " "
                                    << misHeuristicName(c.heuristic) << ": " << m.mean << " +- " << m.standardError
                                    << " expected " << expected);
    EXPECT_GT(m.standardError, 0.0);
    EXPECT_LT(std::abs(m.zScore(expected)), 4.5);  // 5 comparisons
    EXPECT_LT(m.standardError, 0.08 * expected);    // sharp enough to see a lost tail (0.95^1000)
  }
}

using test::zDifference;

test::MeanEstimate seedMeans(const Scene& scene, const RenderSettings& s, int seeds, int passes) {
  return test::seedMeans(scene, s, seeds, passes, 500);
}

// A square emitter of side `side` facing down at height 1 over a Lambertian floor, with the same
// power at every size (Le = power / (pi side^2)); the camera sits below it.
SceneDesc emitterOverFloor(float side, float power) {
  SceneDesc desc = test::floorScene(0.5f);
  const float h = 0.5f * side, Le = power / (kPi * side * side);
  desc.materials.push_back(test::lambertian(0.f, Spectrum(Le)));
  desc.meshes.push_back(test::quad(Vec3(-h, 1, -h), Vec3(h, 1, -h), Vec3(h, 1, h), Vec3(-h, 1, h), 1));
  desc.camera = test::lookAt(Vec3(0.2f, 0.6f, 1.5f), Vec3(0.f), Vec3(0, 1, 0), 1.2f);
  return desc;
}

// Emitters from 1e-6 to 1e4 of the scene's size: PT, BPT and LT agree wherever the technique
// can see the light in a practical number of samples, and the two smallest emitters, of equal
// power, give the same image (both the point-emitter limit, to O(side^2)).
//  - Uniform weights give a pin-sized emitter's s = 0 techniques (the camera path hits it) a
//    share 1/N of its light, which arrives with a probability of about its area: unbiased, but
//    in any practical run a third of the direct light is missing. The balance and power
//    heuristics give those techniques almost nothing, which is the point of them.
//  - Light tracing from a sky-sized emitter almost never lands in view.
TEST(Extremes, EmitterSizeFromAPinToTheSky) {
  const float power = 3.f;
  RenderSettings s;
  s.width = s.height = 12;
  s.maxLength = 3;
  std::vector<test::MeanEstimate> pinBpt;
  for (float side : {1e-6f, 1e-3f, 1.f, 1e4f}) {
    const Scene scene(emitterOverFloor(side, power));
    s.integrator = IntegratorKind::Pt;
    const test::MeanEstimate pt = seedMeans(scene, s, 8, 4);
    ASSERT_GT(pt.mean, 0.0) << side;
    auto expectAgrees = [&](const test::MeanEstimate& m, const char* what) {
      // At most 14 comparisons: |z| < 4.5 keeps the family-wise false-alarm rate below 1e-4.
      EXPECT_LT(std::abs(zDifference(m, pt)), 4.5) << "side " << side << " " << what << ": " << m.mean << " +- "
                                             << m.standardError << " vs pt " << pt.mean << " +- " << pt.standardError;
    };
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
      if (h == MisHeuristic::Uniform && side < 1.f) continue;
      s.integrator = IntegratorKind::Bpt;
      s.mis.heuristic = h;
      const test::MeanEstimate bpt = seedMeans(scene, s, 8, 4);
      expectAgrees(bpt, misHeuristicName(h));
      if (h == MisHeuristic::Balance && side < 1e-2f) pinBpt.push_back(bpt);
    }
    s.mis.heuristic = MisHeuristic::Balance;
    if (side <= 1.f) {
      s.integrator = IntegratorKind::Lt;
      expectAgrees(seedMeans(scene, s, 8, 4), "lt");
    }
  }
  ASSERT_EQ(pinBpt.size(), 2u);
  EXPECT_LT(std::abs(zDifference(pinBpt[0], pinBpt[1])), 4.5) << pinBpt[0].mean << " vs " << pinBpt[1].mean;
}

// A point light 1e-4 above a floor: the floor's irradiance peaks at I / h^2 = 1e8 I under it, and
// half the light lands within sqrt(3) h of that point. Light tracing and every BPT heuristic
// agree there (uniform weights excepted, below), with no discarded sample; at h = 0.1 the path
// tracer and uniform weights agree too. (At h = 1e-4 the
// path tracer would need camera samples inside that 1e-4-wide spot: unbiased, but hopeless.)
// The light is in view, and the (1,1) technique splats its delta image onto the film, which the
// path tracer cannot produce (a ray never hits a point): lengths 2 and 3 are compared.
TEST(Extremes, PointLightNextToASurface) {
  for (float height : {1e-1f, 1e-4f}) {
    SceneDesc desc = test::floorScene(0.5f);
    PunctualLightDesc light;
    light.position = Vec3(0.f, height, 0.f);
    light.intensity = 1e-8f;
    desc.punctualLights = {light};
    desc.camera = test::lookAt(Vec3(0.f, 0.5f, 0.5f), Vec3(0.f), Vec3(0, 1, 0), 0.5f);
    const Scene scene(std::move(desc));
    RenderSettings s;
    s.width = s.height = 12;
    s.maxLength = 3;
    s.techniques = TechniqueSet::parse("k=2;k=3");
    s.integrator = IntegratorKind::Lt;
    const test::MeanEstimate lt = seedMeans(scene, s, 8, 4);
    ASSERT_GT(lt.mean, 0.0);
    std::vector<std::pair<std::string, test::MeanEstimate>> others;
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
      // Uniform weights leave half of the length-2 light to next-event estimation, which meets
      // the spot as rarely as the path tracer does (see EmitterSizeFromAPinToTheSky).
      if (h == MisHeuristic::Uniform && height < 1e-2f) continue;
      s.integrator = IntegratorKind::Bpt;
      s.mis.heuristic = h;
      others.emplace_back(misHeuristicName(h), seedMeans(scene, s, 8, 4));
    }
    if (height > 1e-2f) {
      s.integrator = IntegratorKind::Pt;
      others.emplace_back("pt", seedMeans(scene, s, 8, 4));
    }
    for (const auto& [name, m] : others)
      EXPECT_LT(std::abs(zDifference(m, lt)), 4.5) << "height " << height << " " << name << ": " << m.mean << " +- "
                                             << m.standardError << " vs lt " << lt.mean << " +- " << lt.standardError;
  }
}

// A metal floor of roughness r under a square emitter, seen where it mirrors the light. From
// r = 1e-4 (GGX alpha 1e-8: an exact mirror, kDeltaAlpha) through the first rough value above
// the delta threshold to r = 1: PT and BPT agree at every roughness, the near-delta glossy image
// converges to the mirror's, and MIS keeps the estimate tame (no fireflies: the seed-to-seed
// spread of the image mean stays a few percent).
TEST(Extremes, RoughnessFromMirrorToDiffuse) {
  std::vector<test::MeanEstimate> nearMirror;
  for (float roughness : {1e-4f, 0.04f, 0.2f, 1.f}) {
    SceneDesc desc = test::floorScene(0.5f);
    desc.materials[0].metallicFactor = 1.f;
    desc.materials[0].roughnessFactor = roughness;
    desc.materials[0].baseColorFactor = Vec4(0.9f, 0.9f, 0.9f, 1.f);
    desc.materials.push_back(test::lambertian(0.f, Spectrum(2.f)));
    desc.meshes.push_back(test::quad(Vec3(-.3f, 1, -.3f), Vec3(.3f, 1, -.3f), Vec3(.3f, 1, .3f), Vec3(-.3f, 1, .3f), 1));
    desc.camera = test::lookAt(Vec3(0.f, 0.5f, 1.2f), Vec3(0.f, 0.f, 0.6f), Vec3(0, 1, 0), 1.0f);
    const Scene scene(std::move(desc));
    RenderSettings s;
    s.width = s.height = 12;
    s.maxLength = 3;
    s.integrator = IntegratorKind::Pt;
    const test::MeanEstimate pt = seedMeans(scene, s, 8, 4);
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power}) {
      s.integrator = IntegratorKind::Bpt;
      s.mis.heuristic = h;
      const test::MeanEstimate bpt = seedMeans(scene, s, 8, 4);
      // 8 comparisons: |z| < 4.5.
      EXPECT_LT(std::abs(zDifference(bpt, pt)), 4.5) << "roughness " << roughness << " " << misHeuristicName(h) << ": "
                                               << bpt.mean << " +- " << bpt.standardError << " vs pt " << pt.mean
                                               << " +- " << pt.standardError;
      EXPECT_LT(bpt.standardError, 0.05 * bpt.mean) << "roughness " << roughness << " " << misHeuristicName(h);
      if (h == MisHeuristic::Balance && roughness < 0.1f) nearMirror.push_back(bpt);
    }
    EXPECT_LT(pt.standardError, 0.05 * pt.mean) << "roughness " << roughness << " pt";
  }
  ASSERT_EQ(nearMirror.size(), 2u);
  EXPECT_LT(std::abs(zDifference(nearMirror[0], nearMirror[1])), 4.5)
      << "mirror " << nearMirror[0].mean << " vs alpha 1.6e-3 " << nearMirror[1].mean;
}

// A smooth glass cube (normals outward, ior inside) on a floor under a square emitter, at
// indices from barely refracting (1.0001, below the threshold where refraction is treated as
// not bending) through glass (1.5) to beyond diamond (3: total internal reflection traps most
// light inside): PT and BPT agree. Seen at a grazing 1e-3 rad over the floor as well.
TEST(Extremes, GlassFromIorOneToThreeAndGrazingViews) {
  for (float ior : {1.0001f, 1.5f, 3.f}) {
    for (bool grazing : {false, true}) {
      if (grazing && ior != 1.5f) continue;
      SceneDesc desc = test::floorScene(0.5f);
      Material glass;
      glass.name = "glass";
      glass.metallicFactor = 0.f;
      glass.roughnessFactor = 0.f;
      glass.transmissionFactor = 1.f;
      glass.ior = ior;
      desc.materials.push_back(glass);
      desc.materials.push_back(test::lambertian(0.f, Spectrum(3.f)));
      for (TriangleMesh m : test::inwardBox(0.2f, 1)) {
        for (Vec3& p : m.positions) p.y += 0.2f;
        for (size_t i = 0; i < m.indices.size(); i += 3) std::swap(m.indices[i + 1], m.indices[i + 2]);  // outward
        for (Vec3& n : m.normals) n = -n;
        desc.meshes.push_back(std::move(m));
      }
      desc.meshes.push_back(test::quad(Vec3(-.4f, 1.2f, -.4f), Vec3(.4f, 1.2f, -.4f), Vec3(.4f, 1.2f, .4f),
                                       Vec3(-.4f, 1.2f, .4f), 2));
      desc.camera = grazing ? test::lookAt(Vec3(0.f, 1e-3f, 2.f), Vec3(0.f, 1e-3f, 0.f), Vec3(0, 1, 0), 0.6f)
                            : test::lookAt(Vec3(0.6f, 0.7f, 1.2f), Vec3(0.f, 0.15f, 0.f), Vec3(0, 1, 0), 0.9f);
      const Scene scene(std::move(desc));
      RenderSettings s;
      s.width = s.height = 12;
      s.maxLength = 6;
      s.integrator = IntegratorKind::Pt;
      const test::MeanEstimate pt = seedMeans(scene, s, 8, 4);
      ASSERT_GT(pt.mean, 0.0) << ior;
      s.integrator = IntegratorKind::Bpt;
      const test::MeanEstimate bpt = seedMeans(scene, s, 8, 4);
      // 4 comparisons: |z| < 4.5.
      EXPECT_LT(std::abs(zDifference(bpt, pt)), 4.5) << "ior " << ior << (grazing ? " grazing" : "") << ": " << bpt.mean
                                               << " +- " << bpt.standardError << " vs pt " << pt.mean << " +- "
                                               << pt.standardError;
    }
  }
}

// Long progressive runs (issue 6): 100,000 passes of a pixel whose every sample is exactly Le
// (an emitting furnace of albedo 0, seen by the path tracer and by the s = 0 technique alone)
// read back as Le to float precision. Film sums are double: a float sum would have drifted by
// about 1e-4 relative at this count.
TEST(Extremes, LongRunsDoNotDrift) {
  const float Le = 0.7f;
  const Scene scene(test::furnace(0.f, Le));
  for (const auto& [integrator, spec] : {std::pair{IntegratorKind::Pt, "all"}, std::pair{IntegratorKind::Bpt, "s=0"}}) {
    RenderSettings s;
    s.width = s.height = 1;
    s.maxLength = 2;
    s.integrator = integrator;
    s.techniques = TechniqueSet::parse(spec);
    RenderSession session(scene, s);
    for (int i = 0; i < 100000; ++i) session.renderPass();
    EXPECT_EQ(session.passes(), 100000u);
    EXPECT_NEAR(session.image().at(0, 0).r, Le, 2e-7f) << integratorName(integrator);
  }
}

}  // namespace
}  // namespace pathlab
