// Equiangular sampling in the path tracer (issue 35): in the bundled fog-lamp scene (a point light
// and an area light in thin fog, a table's shadow) the path tracer's image is the same whether
// distance sampling, equiangular sampling or both under MIS place the medium vertex that connects
// to a light, and the same as BPT's, with and without its equiangular technique family E(1, k)
// (core/bpt/equiangular_technique.h). Region means against region
// means, with their standard errors (tests/support/agreement.h). The closed form through a
// scattering medium lit by area lights is media_test.cpp's foggy furnace, run in every mode.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"

#include <gtest/gtest.h>

#include <iostream>

namespace pathlab {
namespace {

TEST(EquiangularRender, FogLampIsTheSameImageUnderEveryMediumSamplingPtAndBpt) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/fog-lamp.gltf"));
  ASSERT_TRUE(scene.hasMedia());
  RenderSettings base;
  base.width = 24, base.height = 18, base.maxLength = 4;
  auto pt = [&](const std::string& name, MediumSampling m, uint64_t seed, int passes) {
    test::EstimatorSpec e = test::estimatorSpec(name, base, IntegratorKind::Pt, MisHeuristic::Power, seed, passes);
    e.settings.mediumSampling = m;
    return e;
  };
  const uint64_t seed = 1000 * test::testSeedBase();
  // BPT without (1,1): that technique alone sees the bulb itself, a point light the path tracer
  // never hits (a bright pixel in BPT's image, none in PT's). The explicit weights renormalise
  // over the rest, which sample every other path of up to four edges.
  test::EstimatorSpec bpt = test::estimatorSpec("bpt", base, IntegratorKind::Bpt, MisHeuristic::Balance, seed + 4, 512);
  bpt.settings.techniques = TechniqueSet::parse("s=0;t=2;t=3;t=4;2,1;3,1;4,1");
  // BPT with the equiangular family E(1, k): on the same subset (explicit weights), and with every
  // technique (the partial sums, explicit where E can sample the path), beside and in place of
  // C(1, k), under the balance and the power heuristic.
  auto bptWith = [&](const std::string& name, MediumSampling m, MisHeuristic h, bool subset, uint64_t s, int passes) {
    test::EstimatorSpec e = test::estimatorSpec(name, base, IntegratorKind::Bpt, h, s, passes);
    e.settings.mediumSampling = m;
    if (subset) e.settings.techniques = bpt.settings.techniques;
    return e;
  };
  const std::vector<test::EstimatorSpec> estimators = {
      pt("pt distance", MediumSampling::Distance, seed + 1, 2048),
      pt("pt equiangular", MediumSampling::Equiangular, seed + 2, 1024),
      pt("pt mis", MediumSampling::Mis, seed + 3, 1024),
      bpt,
      bptWith("bpt subset mis", MediumSampling::Mis, MisHeuristic::Balance, true, seed + 5, 512),
      bptWith("bpt distance", MediumSampling::Distance, MisHeuristic::Balance, false, seed + 6, 512),
      bptWith("bpt mis", MediumSampling::Mis, MisHeuristic::Balance, false, seed + 7, 512),
      bptWith("bpt equiangular", MediumSampling::Equiangular, MisHeuristic::Power, false, seed + 8, 512),
      // E(1, k) follows C(1, k)'s switch: here only E(1, 2) runs, and no weight counts E(1, 3) or E(1, 4).
      [&] {
        test::EstimatorSpec e = bptWith("bpt some mis", MediumSampling::Mis, MisHeuristic::Balance, false, seed + 9, 512);
        e.settings.techniques = TechniqueSet::parse("s=0;s=2;s=3;t=1;1,2");
        return e;
      }()};
  const test::PixelLabels grid = test::gridLabels(base.width, base.height, 3, 3);
  const auto run = test::runAgreement(scene, estimators, {grid},
                                      {{"pt equiangular", "pt distance"},
                                       {"pt mis", "pt distance"},
                                       {"pt mis", "pt equiangular"},
                                       {"pt mis", "bpt"},
                                       {"pt equiangular", "bpt"},
                                       {"pt mis", "bpt subset mis"},
                                       {"bpt", "bpt subset mis"},
                                       {"bpt mis", "bpt distance"},
                                       {"bpt equiangular", "bpt distance"},
                                       {"bpt equiangular", "bpt mis"},
                                       {"bpt some mis", "bpt distance"}},
                                      test::kFamilyAlpha);
  test::report(run, "fog lamp: medium sampling");
  test::expectAgreement(run, "fog lamp: medium sampling");
}

}  // namespace
}  // namespace pathlab
