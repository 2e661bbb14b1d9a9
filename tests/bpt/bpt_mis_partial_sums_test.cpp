// The O(1) MIS weights from the walks' partial sums (mis_partial_sums.h) against the explicit
// O(n) misWeight, their oracle: on random subpaths of every bundled scene and of scenes with
// delta lights, delta BSDFs, a pinhole and a thin lens, for every connectable (s, t), under every
// heuristic, with one light subpath per camera sample and with another light-tracing ratio, they
// agree to 1e-5 relative, and the interior techniques' own entry point (misWeightInterior, the
// tracer's image-only path) gives the same bits. Where the sums must not answer (a connection shorter than
// MisOptions::minConnection) they decline and misWeight is used.
#include "core/bpt/bidir_tracer.h"
#include "core/bpt/connect.h"
#include "core/bpt/mis_partial_sums.h"
#include "core/lights/environment_file.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>

namespace pathlab {
namespace {

struct Tally {
  int compared = 0, declined = 0;
  int interior = 0;  // of them, interior techniques (s, t >= 2) also weighed by misWeightInterior
};

// Every connectable technique of `samples` random subpath pairs, under each heuristic.
Tally compare(const Scene& scene, const Camera& camera, int maxLength, float lightTracingRatio, float minConnection,
              const std::string& name, int samples = 400) {
  Pcg32 rng(2026, 12);
  CameraSubpath cp;
  LightSubpath lp;
  SubpathMisSums cameraSums, lightSums;
  Counters counters;
  Tally tally;
  const MisOptions options[] = {{MisHeuristic::Balance, 2.f, minConnection},
                                {MisHeuristic::Power, 2.f, minConnection},
                                {MisHeuristic::Power, 1.37f, minConnection},
                                {MisHeuristic::Uniform, 2.f, minConnection},
                                {MisHeuristic::VarianceAware, 2.f, minConnection}};
  // Variance-aware: a factor per technique of each length (by slot), log-uniform over 1e-2..1e2,
  // drawn afresh for every sample; the sums then keep their steps (SubpathMisSums::step).
  std::vector<std::vector<float>> factors(static_cast<size_t>(maxLength) + 1);
  const TechniqueSet all = TechniqueSet::all();
  const float minDistance = minConnection * scene.bounds().radius;
  for (int sample = 0; sample < samples; ++sample) {
    const Vec2 pRaster(rng.next1D() * static_cast<float>(camera.width()), rng.next1D() * static_cast<float>(camera.height()));
    const int nt = generateCameraSubpath(scene, camera, pRaster, rng.next2D(), rng, WalkOptions{maxLength + 1, true, scene.mediumAt(camera.position())}, cp,
                                         counters);
    const int ns = generateLightSubpath(scene, rng, WalkOptions{maxLength, true}, lp, counters);
    for (int k = 1; k <= maxLength; ++k) {
      factors[static_cast<size_t>(k)].resize(static_cast<size_t>(2 * k));
      for (float& c : factors[static_cast<size_t>(k)]) c = std::pow(10.f, -2.f + 4.f * rng.next1D());
    }
    for (const MisOptions& o : options) {
      const MisPower power(o);
      const bool varianceAware = o.heuristic == MisHeuristic::VarianceAware;
      accumulateCameraSums(cp, power, lightTracingRatio, cameraSums, {}, varianceAware);
      accumulateLightSums(lp, power, lightSums, {}, varianceAware);
      for (int t = 1; t <= nt; ++t)
        for (int s = 0; s <= std::max(ns, 1) && s + t - 1 <= maxLength; ++s) {
          if (s + t < 2 || (s > ns && !(s == 1 && t >= 2))) continue;
          Pcg32 connectionRng(static_cast<uint64_t>(sample), static_cast<uint64_t>(s * 64 + t));
          Connection c;
          if (!formConnection(scene, camera, lp, s, cp, t, connectionRng, c)) continue;
          const MisPath path{lp.data(), s, cp.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
          const float* f = varianceAware ? factors[static_cast<size_t>(s + t - 1)].data() : nullptr;
          const float explicitWeight = misWeight(scene, camera, path, all, o, lightTracingRatio, f);
          const std::optional<float> fast =
              misWeightFromSums(scene, camera, path, lightSums, cameraSums, power, lightTracingRatio, minDistance, f);
          if (s >= 2 && t >= 2) {
            // The tracer's image-only path weighs interior techniques with misWeightInterior: the same answer, bit
            // for bit, declining where this one declines.
            const std::optional<float> interior = misWeightInterior(scene, lp, s, cp, t, c.pdfs, c.edgeLength2, lightSums,
                                                                    cameraSums, power, lightTracingRatio, minDistance, f);
            ++tally.interior;
            EXPECT_EQ(interior.has_value(), fast.has_value()) << name << " (" << s << "," << t << ")";
            if (interior && fast) {
              EXPECT_EQ(std::bit_cast<uint32_t>(*interior), std::bit_cast<uint32_t>(*fast))
                  << name << " (" << s << "," << t << ") " << misHeuristicName(o.heuristic) << ": " << *interior
                  << " vs " << *fast;
            }
          }
          if (!fast) {
            ++tally.declined;
            continue;
          }
          ++tally.compared;
          EXPECT_NEAR(*fast, explicitWeight, 1e-5f * std::max(explicitWeight, 1e-3f))
              << name << " (" << s << "," << t << ") " << misHeuristicName(o.heuristic) << " beta " << o.beta
              << " ratio " << lightTracingRatio;
          if (::testing::Test::HasFailure()) return tally;
        }
    }
  }
  return tally;
}

Scene bundled(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

// minInterior: interior techniques (s, t >= 2) compared at each ratio (few where most camera paths
// escape to an environment or end on a point light).
void checkScene(const Scene& scene, const std::string& name, int maxLength, const LensOptions& lens = {},
                int minInterior = 100) {
  const Camera camera(scene.cameraDesc(), 16, 12, lens);
  for (const float ratio : {1.f, 2.5f}) {
    const Tally tally = compare(scene, camera, maxLength, ratio, kDefaultMinConnection, name);
    // Enough weights compared to mean something, and the sums answered nearly always.
    EXPECT_GT(tally.compared, 1000) << name << " ratio " << ratio;
    EXPECT_LT(tally.declined, tally.compared / 100 + 1) << name;
    EXPECT_GE(tally.interior, minInterior) << name << " ratio " << ratio;
  }
}

TEST(MisPartialSums, EqualTheExplicitWeightsOnTheCornellBox) { checkScene(bundled("cornell-box"), "cornell-box", 8); }
TEST(MisPartialSums, EqualTheExplicitWeightsOnVeachMis) { checkScene(bundled("veach-mis"), "veach-mis", 6); }
TEST(MisPartialSums, EqualTheExplicitWeightsOnBidirLamp) { checkScene(bundled("bidir-lamp"), "bidir-lamp", 8); }
TEST(MisPartialSums, EqualTheExplicitWeightsOnCaustic) { checkScene(bundled("caustic"), "caustic", 8); }
// Medium vertices (issue 16): fog, a glass sphere and absorbing glass, a camera in the fog.
TEST(MisPartialSums, EqualTheExplicitWeightsInFog) { checkScene(bundled("fog"), "fog", 8); }
// Delta BSDFs (mirror, glass) with an area light and with a point light, seen by a pinhole.
TEST(MisPartialSums, EqualTheExplicitWeightsWithDeltaComponents) {
  checkScene(Scene(test::deltaScene(test::DeltaLight::Area)), "delta/area", 7);
  checkScene(Scene(test::deltaScene(test::DeltaLight::Point)), "delta/point", 7);
}
// An environment light (the bundled sky map) with a glossy and a glass sphere: escaping camera
// paths (s = 0), next-event estimation toward it and light subpaths from it, at infinity.
TEST(MisPartialSums, EqualTheExplicitWeightsUnderAnEnvironment) {
  const std::string source = PATHLAB_SOURCE_DIR;
  LoadOptions load;
  load.environment = std::make_shared<EnvironmentDesc>(readEnvironment(source + "/assets/sky.hdr"));
  checkScene(Scene(loadGltf(source + "/assets/environment.gltf", load)), "environment", 6, {}, 10);
  // The default light (a constant environment) where the file has none.
  load.environment = nullptr;
  load.defaultLight = true;
  checkScene(Scene(loadGltf(source + "/assets/environment.gltf", load)), "environment/default", 6, {}, 10);
}
// Next-event estimation choosing by a light BVH (issue 15): x0's density under technique (1, t)
// depends on the receiver x1, so the sums carry its ratio to the light subpath's power choice.
// many-lights: a sun, a point lamp and eight lanterns; punctual: point, spot and sun; the
// environment (a map and no other light) with the BVH forced: the tree is empty, the map alone.
TEST(MisPartialSums, EqualTheExplicitWeightsAmongManyLights) {
  const Scene many = bundled("many-lights");
  ASSERT_TRUE(many.lights().neeByContext());
  checkScene(many, "many-lights", 6);
  const std::string source = PATHLAB_SOURCE_DIR;
  LoadOptions load;
  load.lightSelection = LightSelection::Bvh;
  checkScene(Scene(loadGltf(source + "/tests/scenes/punctual.gltf", load)), "punctual/bvh", 6, {}, 0);
  load.environment = std::make_shared<EnvironmentDesc>(readEnvironment(source + "/assets/sky.hdr"));
  checkScene(Scene(loadGltf(source + "/assets/environment.gltf", load)), "environment/bvh", 6, {}, 10);
}
// A thin lens: the t = 1 technique's lens point and the camera subpath's differ in density.
TEST(MisPartialSums, EqualTheExplicitWeightsThroughAThinLens) {
  checkScene(bundled("cornell-box"), "cornell-box/lens", 6, LensOptions{0.05f, 3.f});
}

// An orthographic camera (issue 15): the camera vertex cannot be connected to (t = 1) and the
// first camera vertex's density is planar, as from a directional light.
TEST(MisPartialSums, EqualTheExplicitWeightsThroughAnOrthographicCamera) {
  const Scene scene = bundled("cornell-box");
  CameraDesc ortho = scene.cameraDesc();
  ortho.orthographic = Vec2(0.4f, 0.3f);
  const Camera camera(ortho, 16, 12);
  const Tally tally = compare(scene, camera, 8, 1.f, kDefaultMinConnection, "cornell-box/orthographic");
  EXPECT_GT(tally.compared, 1000);
  EXPECT_LT(tally.declined, tally.compared / 100 + 1);
}

// With connections shorter than 30 % of the bounding radius left out, the sums decline those
// paths (misWeight then applies the rule) and agree wherever they answer.
TEST(MisPartialSums, DeclineNearCoincidentConnections) {
  const Scene scene = bundled("cornell-box");
  const Camera camera(scene.cameraDesc(), 16, 12);
  const Tally tally = compare(scene, camera, 6, 1.f, 0.3f, "cornell-box/min-connection");
  EXPECT_GT(tally.declined, 500);
  EXPECT_GT(tally.compared, 500);
}

}  // namespace
}  // namespace pathlab
