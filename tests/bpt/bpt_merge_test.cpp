// Vertex merging: each merge length estimates the same image as the connections of that length
// (the radius's bias held below the test's resolution), vertex connection and merging agrees with
// BPT, and the merge pass is the same at any thread count.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"
#include "tests/support/bpt_scenes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <iostream>

namespace pathlab {
namespace {

constexpr int kMergeImageSize = 24;

// In the integrating sphere (bpt_scenes.h) every surface is Lambertian and no edge is concave:
// a merge's blur moves no light across a corner, so its bias is only the kernel's curvature
// term, far below the noise at these radii.
const Scene& mergeSphere() {
  static const Scene scene(test::integratingSphere());
  return scene;
}

RenderSettings mergeSettings(const std::string& techniques, uint64_t seed, float radius = 0.02f) {
  RenderSettings s;
  s.width = s.height = kMergeImageSize;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse(techniques);
  s.mergeRadius = radius;
  s.mergeRadiusAlpha = 1.f;
  s.seed = 1000 * test::testSeedBase() + seed;
  return s;
}

TEST(VertexMerging, EachMergeLengthEstimatesTheConnectionsImageOfItsLength) {
  const Scene& scene = mergeSphere();
  const test::PixelLabels grid = test::gridLabels(kMergeImageSize, kMergeImageSize, 2, 2);
  std::vector<test::EstimatorSpec> estimators;
  std::vector<test::PairSpec> pairs;
  for (int k = 2; k <= 4; ++k) {
    const std::string c = "k=" + std::to_string(k), m = "m=" + std::to_string(k);
    estimators.push_back({c, mergeSettings(c, 10 + static_cast<uint64_t>(k)), 64});
    estimators.push_back({m, mergeSettings(m, 20 + static_cast<uint64_t>(k)), 64});
    pairs.push_back({m, c, 0, 0.1});
    // A quarter of the light vertices kept (none is caustic here), each standing for four.
    RenderSettings thinned = mergeSettings(m, 30 + static_cast<uint64_t>(k));
    thinned.mergeNonCaustic = 0.25f;
    estimators.push_back({m + ", non-caustic 0.25", thinned, 64});
    pairs.push_back({m + ", non-caustic 0.25", c, 0, 0.1});
  }
  const auto run = test::runAgreement(scene, estimators, {grid}, pairs, test::kFamilyAlpha);
  std::cout << run.summary();
  test::expectAgreement(run, "merges against connections, by length");
}

TEST(VertexMerging, ConnectionsAndMergesTogetherAgreeWithBpt) {
  // The integrating sphere, and a glass sphere's caustic, where the merges take the paths
  // light -> glass -> glass -> floor -> camera that only light tracing and s = 0 connect: with
  // every light vertex kept for merging, and with the non-caustic ones thinned.
  static const Scene caustic(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/caustic.gltf"));
  const std::vector<std::pair<const char*, const Scene*>> scenes = {{"integrating sphere", &mergeSphere()},
                                                                    {"caustic", &caustic}};
  for (const auto& [name, scene] : scenes) {
    const test::PixelLabels grid = test::gridLabels(kMergeImageSize, kMergeImageSize, 3, 3);
    // And with a fifth of the non-caustic light vertices kept for merging (each standing for five,
    // their merges' densities a fifth: mergeKeep), the caustic ones all kept.
    RenderSettings thinned = mergeSettings("all;m=all", 33, 0.01f);
    thinned.mergeNonCaustic = 0.2f;
    const std::vector<test::EstimatorSpec> estimators = {{"bpt", mergeSettings("all", 31), 128},
                                                         {"vcm", mergeSettings("all;m=all", 32, 0.01f), 128},
                                                         {"vcm, non-caustic 0.2", thinned, 128}};
    const auto run = test::runAgreement(*scene, estimators, {grid},
                                        {{"vcm", "bpt", 0, 0.05}, {"vcm, non-caustic 0.2", "bpt", 0, 0.05}},
                                        test::kFamilyAlpha);
    std::cout << run.summary();
    test::expectAgreement(run, name);
  }
}

// Progressive photon mapping (--integrator ppm): the merges at each camera subpath's first
// non-specular vertex and the camera subpaths that hit a light, MIS-weighted where both sample a
// path, estimate BPT's image: on the integrating sphere and through the caustic's glass.
TEST(VertexMerging, ProgressivePhotonMappingAgreesWithBpt) {
  static const Scene caustic(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/caustic.gltf"));
  const std::vector<std::pair<const char*, const Scene*>> scenes = {{"integrating sphere", &mergeSphere()},
                                                                    {"caustic", &caustic}};
  for (const auto& [name, scene] : scenes) {
    const test::PixelLabels grid = test::gridLabels(kMergeImageSize, kMergeImageSize, 3, 3);
    RenderSettings ppm = mergeSettings("s=0;m=all", 42, 0.02f);
    ppm.mergeSite = MergeSite::FirstNonSpecular;
    const std::vector<test::EstimatorSpec> estimators = {{"bpt", mergeSettings("all", 41), 128}, {"ppm", ppm, 128}};
    const auto run = test::runAgreement(*scene, estimators, {grid}, {{"ppm", "bpt", 0, 0.05}}, test::kFamilyAlpha);
    std::cout << run.summary();
    test::expectAgreement(run, name);
  }
}

// The MIS check (checkMis) sums, on every connection the render forms, the weights of every
// technique of its length, connections and merges: one on each.
TEST(VertexMerging, TheWeightsOverConnectionsAndMergesSumToOneOnEveryPath) {
  // One pass of `s` under heuristic h with the MIS check on: its counters.
  auto checkedPass = [](RenderSettings s, MisHeuristic h, float nonCaustic) {
    s.mis.heuristic = h;
    s.mergeNonCaustic = nonCaustic;
    s.checkMis = true;
    RenderSession session(mergeSphere(), s);
    session.renderPass();
    return session.counters();
  };
  for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform})
    for (const float nonCaustic : {1.f, 0.3f}) {
      const Counters vcm = checkedPass(mergeSettings("all;m=all", 7, 0.05f), h, nonCaustic);
      EXPECT_GT(vcm.misPartitionChecks, 1000u) << misHeuristicName(h);
      EXPECT_EQ(vcm.misPartitionFailures, 0u) << misHeuristicName(h) << " non-caustic " << nonCaustic;
      // Progressive photon mapping: the camera paths that hit a light and the one merge at their
      // first non-specular vertex.
      RenderSettings ppm = mergeSettings("s=0;m=all", 8, 0.05f);
      ppm.mergeSite = MergeSite::FirstNonSpecular;
      const Counters ppmCounters = checkedPass(ppm, h, nonCaustic);
      EXPECT_GT(ppmCounters.misPartitionChecks, 100u) << misHeuristicName(h);
      EXPECT_EQ(ppmCounters.misPartitionFailures, 0u) << "ppm " << misHeuristicName(h) << " non-caustic " << nonCaustic;
    }
}

TEST(VertexMerging, TheSameImageAtAnyThreadCount) {
  RenderSettings s = mergeSettings("all;m=all", 5);
  s.mergeNonCaustic = 0.3f;  // the pass's keep decisions too
  auto render = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
    RenderSession session(mergeSphere(), s);
    for (int p = 0; p < 3; ++p) session.renderPass();
    return session.image();
  };
  const Image one = render(1);
  EXPECT_EQ(render(2).rgb, one.rgb);
  EXPECT_EQ(render(4).rgb, one.rgb);
}

}  // namespace
}  // namespace pathlab
