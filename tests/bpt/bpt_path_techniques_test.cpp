// One path, every technique (core/bpt/path_techniques.h): for paths formed by every connectable
// technique on random subpaths of the loadBundled scenes and of a scene with a point light, a mirror
// and glass, the absolute densities p_{s',t'}(x) agree with the weights the renderer uses: the
// balance weight of each technique is its density over the sum of the possible ones', the own
// technique's weights equal misWeight under each heuristic, the density ratios equal
// techniqueDensityRatios, and the impossible techniques are exactly those sampleableTechniques
// leaves out, with zero density and weight.
#include "core/bpt/path_techniques.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/random_connections.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

void checkTechniquesOnPath(const Scene& scene, const std::string& name, int maxLength) {
  const Camera camera(scene.cameraDesc(), 16, 12, LensOptions{});
  const TechniqueSet all = TechniqueSet::all();
  const MisOptions options{MisHeuristic::Balance, 2.f, 0.f};  // no short-connection rule: plain ratios
  int compared = 0;
  test::forEachConnection(scene, camera, maxLength, 200, Pcg32(77, 3), [&](const MisPath& path, int s, int t) {
    const std::vector<TechniqueOnPath> every = techniquesOnPath(scene, camera, path, all, options);
    ASSERT_EQ(static_cast<int>(every.size()), s + t) << name;
    const uint64_t sampleable = sampleableTechniques(path);
    std::vector<double> ratios(static_cast<size_t>(s + t));
    techniqueDensityRatios(scene, camera, path, ratios.data());
    double sum = 0.0, weights = 0.0;
    for (const TechniqueOnPath& x : every) {
      ASSERT_EQ(x.possible, ((sampleable >> x.s) & 1u) != 0) << name;
      if (!x.possible) {
        EXPECT_EQ(x.pdfA, 0.0);
        EXPECT_EQ(x.balance, 0.0);
      }
      sum += x.pdfA;
      weights += x.balance;
    }
    const TechniqueOnPath& own = every[static_cast<size_t>(s)];
    if (!(own.pdfA > 0.0) || !std::isfinite(sum) || !(sum > 0.0)) return;
    EXPECT_NEAR(weights, 1.0, 1e-6) << name;
    for (const TechniqueOnPath& x : every) {
      if (!x.possible) continue;
      EXPECT_NEAR(x.balance, x.pdfA / sum, 1e-5 * std::max(x.balance, 1e-3)) << name << " (" << x.s << "," << x.t << ")";
      EXPECT_NEAR(x.pdfA / own.pdfA, ratios[static_cast<size_t>(x.s)], 1e-5 * ratios[static_cast<size_t>(x.s)]) << name;
    }
    for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
      MisOptions o = options;
      o.heuristic = h;
      const double expected = misWeight(scene, camera, path, all, o);
      const double got = h == MisHeuristic::Balance ? own.balance : h == MisHeuristic::Power ? own.power : own.uniform;
      EXPECT_NEAR(got, expected, 1e-5 * std::max(expected, 1e-3)) << name << " " << misHeuristicName(h);
    }
    ++compared;
  });
  EXPECT_GT(compared, 300) << name;
}

Scene loadBundled(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

TEST(TechniquesOnPath, AgreeWithTheWeightsOnTheCornellBox) { checkTechniquesOnPath(loadBundled("cornell-box"), "cornell-box", 6); }
TEST(TechniquesOnPath, AgreeWithTheWeightsOnVeachMis) { checkTechniquesOnPath(loadBundled("veach-mis"), "veach-mis", 5); }
TEST(TechniquesOnPath, AgreeWithTheWeightsOnTheCausticScene) { checkTechniquesOnPath(loadBundled("caustic"), "caustic", 6); }
TEST(TechniquesOnPath, AgreeWithTheWeightsWithDeltaLightAndGlass) {
  checkTechniquesOnPath(Scene(test::deltaScene(test::DeltaLight::Point)), "delta scene", 6);
}

}  // namespace
}  // namespace pathlab
