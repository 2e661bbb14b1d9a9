// The O(1) MIS weights over connections and merges (mis_partial_sums.h with MergeTerms) against
// the explicit O(n) weights over both families (merge_mis.h), their oracle: on random subpath
// pairs of the bundled scenes, for every connectable (s, t) and for the merge of every mergeable
// light vertex with every mergeable camera vertex, under balance, power and uniform, with every
// connection and merge enabled (vcm) and with the merges alone (bpm), at an eta below, near and
// above the paths' densities, keeping every light vertex or thinning the non-caustic ones
// (mergeKeep), they agree to 1e-5 relative.
#include "core/bpt/connect.h"
#include "core/bpt/merge_mis.h"
#include "core/bpt/mis_partial_sums.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/bpt_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

struct MergeSumsTally {
  int connections = 0, merges = 0, declined = 0;
};

MergeSumsTally compareWithMerges(const Scene& scene, const Camera& camera, int maxLength, bool withConnections,
                                 const std::string& name, int samples = 150) {
  Pcg32 rng(2026, 32);
  CameraSubpath cp;
  LightSubpath lp;
  SubpathMisSums cameraSums, lightSums;
  std::vector<double> storedSum;
  std::vector<float> storedShortest;
  Counters counters;
  MergeSumsTally tally;
  const float minConnection = kDefaultMinConnection;
  const MisOptions options[] = {{MisHeuristic::Balance, 2.f, minConnection},
                                {MisHeuristic::Power, 2.f, minConnection},
                                {MisHeuristic::Power, 1.37f, minConnection},
                                {MisHeuristic::Uniform, 2.f, minConnection}};
  const TechniqueSet techniques =
      withConnections ? TechniqueSet::parse("all;m=all") : TechniqueSet::allMerges();
  const float minDistance = minConnection * scene.bounds().radius;
  const float ratio = 1.f;
  for (int sample = 0; sample < samples; ++sample) {
    const Vec2 pRaster(rng.next1D() * static_cast<float>(camera.width()), rng.next1D() * static_cast<float>(camera.height()));
    const int nt = generateCameraSubpath(scene, camera, pRaster, rng.next2D(), rng,
                                         WalkOptions{maxLength + 1, true, scene.mediumAt(camera.position())}, cp, counters);
    const int ns = generateLightSubpath(scene, rng, WalkOptions{maxLength, true}, lp, counters);
    for (const double eta : {1e-3, 0.7, 300.0})
      for (const MisOptions& o : options)
      for (const double nonCaustic : {1.0, 0.15}) {
        const MisPower power(o);
        const MergeTerms terms{withConnections ? 1.0 : 0.0, true, eta, nonCaustic};
        const MergeMis merge{eta, false, nonCaustic};
        accumulateCameraSums(cp, power, ratio, cameraSums, terms);
        accumulateLightSums(lp, power, lightSums, terms);
        storedSum.assign(static_cast<size_t>(std::max(ns, 1)), 0.0);
        storedShortest.assign(static_cast<size_t>(std::max(ns, 1)), 0.f);
        accumulateLightSums(lp.data(), ns, power, storedSum.data(), storedShortest.data(), terms);
        // The stored form is the subpath form without its last entry.
        for (int i = 0; i < ns; ++i) {
          EXPECT_EQ(storedSum[static_cast<size_t>(i)], lightSums.sum[static_cast<size_t>(i)]) << name;
          EXPECT_EQ(storedShortest[static_cast<size_t>(i)], lightSums.shortestEdge2[static_cast<size_t>(i)]) << name;
        }
        // Connections (their weights now count the merges).
        for (int t = 1; withConnections && t <= nt; ++t)
          for (int s = 0; s <= std::max(ns, 1) && s + t - 1 <= maxLength; ++s) {
            if (s + t < 2 || (s > ns && !(s == 1 && t >= 2))) continue;
            Pcg32 connectionRng(static_cast<uint64_t>(sample), static_cast<uint64_t>(s * 64 + t));
            Connection c;
            if (!formConnection(scene, camera, lp, s, cp, t, connectionRng, c)) continue;
            const MisPath path{lp.data(), s, cp.data(), t, c.hasSampled ? &c.sampled : nullptr, &c.pdfs};
            const float oracle =
                weightWithMerges(scene, camera, path, Technique{s, t}, techniques, o, ratio, minDistance, merge);
            const std::optional<float> fast =
                s >= 2 && t >= 2 ? misWeightInterior(scene, lp, s, cp, t, c.pdfs, c.edgeLength2, lightSums, cameraSums,
                                                     power, ratio, minDistance, terms)
                                 : misWeightFromSums(scene, camera, path, lightSums, cameraSums, power, ratio,
                                                     minDistance, terms);
            if (!fast) {
              ++tally.declined;
              continue;
            }
            ++tally.connections;
            EXPECT_NEAR(*fast, oracle, 1e-5f * std::max(oracle, 1e-3f))
                << name << " C(" << s << "," << t << ") " << misHeuristicName(o.heuristic) << " beta " << o.beta
                << " eta " << eta << " non-caustic " << nonCaustic;
            if (::testing::Test::HasFailure()) return tally;
          }
        // Merges of every mergeable light vertex y(s-1) with every mergeable camera vertex z(t-1):
        // the weights are functions of the two subpaths, near or not.
        for (int t = 2; t <= nt; ++t) {
          const PathVertex& z = cp[t - 1];
          if (!mergeableVertex(z)) continue;
          for (int s = 2; s <= ns && s + t - 2 <= maxLength; ++s) {
            const PathVertex& y = lp[s - 1];
            if (!mergeableVertex(y)) continue;
            const BsdfEval f = cp.bsdf(t - 1).eval(z.wo, y.wo, TransportMode::Radiance);
            const MergePdfs pdfs{f.pdfFwdW, f.pdfRevW};
            const float oracle = mergeWeight(lp.data(), s, cp.data(), t, pdfs, techniques, o, ratio, minDistance, merge);
            const std::optional<float> fast =
                mergeWeightFromSums(scene, lp.data(), s, storedSum.data(), storedShortest.data(), cp, t, cameraSums,
                                    pdfs, power, ratio, minDistance, terms);
            if (!fast) {
              ++tally.declined;
              continue;
            }
            ++tally.merges;
            EXPECT_NEAR(*fast, oracle, 1e-5f * std::max(oracle, 1e-3f))
                << name << " M(" << s << "," << t << ") " << misHeuristicName(o.heuristic) << " beta " << o.beta
                << " eta " << eta << " non-caustic " << nonCaustic;
            if (::testing::Test::HasFailure()) return tally;
          }
        }
      }
  }
  return tally;
}

// minMerges: merges compared per family choice (few where light paths end on delta surfaces or
// escape).
void checkMergeSums(const Scene& scene, const std::string& name, int maxLength, int minMerges = 1000) {
  const Camera camera(scene.cameraDesc(), 16, 12);
  for (const bool withConnections : {true, false}) {
    const MergeSumsTally tally = compareWithMerges(scene, camera, maxLength, withConnections, name);
    if (withConnections) {
      EXPECT_GT(tally.connections, 1000) << name;
    }
    EXPECT_GT(tally.merges, minMerges) << name << (withConnections ? " vcm" : " bpm");
    EXPECT_LT(tally.declined, (tally.connections + tally.merges) / 50 + 1) << name;
  }
}

Scene bundledScene(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

TEST(MergeMisSums, EqualTheExplicitWeightsOnTheCornellBox) { checkMergeSums(bundledScene("cornell-box"), "cornell-box", 8); }
// A mirror and a glass sphere: delta vertices beside merged ones, camera ends that are delta.
TEST(MergeMisSums, EqualTheExplicitWeightsOnCornellSpheres) {
  checkMergeSums(bundledScene("cornell-spheres"), "cornell-spheres", 8);
}
TEST(MergeMisSums, EqualTheExplicitWeightsOnCaustic) { checkMergeSums(bundledScene("caustic"), "caustic", 8); }
// Next-event estimation by a light BVH: x0's density under (1, t) differs from its origin's.
TEST(MergeMisSums, EqualTheExplicitWeightsAmongManyLights) {
  checkMergeSums(bundledScene("many-lights"), "many-lights", 6, 300);
}
TEST(MergeMisSums, EqualTheExplicitWeightsWithDeltaComponents) {
  checkMergeSums(Scene(test::deltaScene(test::DeltaLight::Area)), "delta/area", 7);
  checkMergeSums(Scene(test::deltaScene(test::DeltaLight::Point)), "delta/point", 7, 300);
}

}  // namespace
}  // namespace pathlab
