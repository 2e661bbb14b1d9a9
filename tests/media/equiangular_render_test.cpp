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
      // E(1, k) has its own switch: here E(1, 2) runs beside C(1, 2), E(1, 3) without C(1, 3), and
      // neither C(1, 4) nor E(1, 4) runs (no weight counts them).
      [&] {
        test::EstimatorSpec e = bptWith("bpt some mis", MediumSampling::Mis, MisHeuristic::Balance, false, seed + 9, 512);
        e.settings.techniques = TechniqueSet::parse("s=0;s=2;s=3;t=1;1,2;E1,2;E1,3");
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

Image pyramidSum(const RenderSession& session, int length) {
  const Image full = session.image();
  Image sum{full.width, full.height, std::vector<float>(full.rgb.size(), 0.f)};
  for (const Technique x : techniquesUpTo(length, TechniqueFamilies::Connections | TechniqueFamilies::Equiangular)) {
    const Image share = session.techniqueImage(x, false);
    for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += share.rgb[i];
  }
  return sum;
}

double luminanceSum(const Image& img) {
  double sum = 0.0;
  for (float v : img.rgb) sum += v;
  return sum;
}

// E(1, k) is a technique of the pyramid like any other: its own weighted and unweighted buffers,
// the weighted shares of connections and equiangular techniques summing to the image (Veach's eq.
// 10.9 with E among the techniques), and an isolated E(1, k) rendering exactly its buffer. A scene
// without a medium E can sample keeps no buffer for it.
TEST(EquiangularRender, TheEquiangularTechniquesArePyramidTechniques) {
  const Scene fog(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/fog-lamp.gltf"));
  RenderSettings s;
  s.width = 20, s.height = 16, s.maxLength = 4, s.pyramidLength = 4, s.seed = 17;
  s.integrator = IntegratorKind::Bpt;
  s.mediumSampling = MediumSampling::Mis;
  for (const auto& [heuristic, spec] : {std::pair{MisHeuristic::Balance, "all"}, std::pair{MisHeuristic::Power, "all"},
                                        std::pair{MisHeuristic::Balance, "s=0;s=2;t=1;1,2;E1,3"}}) {
    RenderSettings h = s;
    h.mis.heuristic = heuristic;
    h.techniques = TechniqueSet::parse(spec);
    RenderSession session(fog, h);
    ASSERT_TRUE(covers(session.pyramidFamilies(), TechniqueKind::Equiangular));
    for (int i = 0; i < 3; ++i) session.renderPass();
    SCOPED_TRACE(spec);
    const Image full = session.image(), sum = pyramidSum(session, 4);
    ASSERT_GT(luminanceSum(full), 0.0);
    for (size_t i = 0; i < full.rgb.size(); ++i)
      ASSERT_NEAR(full.rgb[i], sum.rgb[i], 1e-4 * std::max(std::abs(full.rgb[i]), std::abs(sum.rgb[i])) + 1e-7)
          << "sum of weighted shares vs image at value " << i;
    const Technique e3 = Technique::equiangular(3);
    EXPECT_GT(luminanceSum(session.techniqueImage(e3, false)), 0.0) << "E(1,3) has a share";
    EXPECT_GT(luminanceSum(session.techniqueImage(e3, true)), 0.0) << "E(1,3) has an estimate";
  }
  // Isolated, E(1, 2) and E(1, 3) are their buffers, weighted and unweighted.
  RenderSession pyramid(fog, s);
  for (int i = 0; i < 2; ++i) pyramid.renderPass();
  for (const int t : {2, 3})
    for (const bool unweighted : {false, true}) {
      RenderSettings iso = s;
      iso.pyramidLength = 0;
      iso.isolate = Isolation{1, t, unweighted, TechniqueKind::Equiangular};
      RenderSession session(fog, iso);
      for (int i = 0; i < 2; ++i) session.renderPass();
      SCOPED_TRACE(testing::Message() << "E(1," << t << ")" << (unweighted ? " unweighted" : " weighted"));
      const Image expected = pyramid.techniqueImage(Technique::equiangular(t), unweighted);
      const Image got = session.image();
      ASSERT_GT(luminanceSum(expected), 0.0);
      for (size_t i = 0; i < got.rgb.size(); ++i)
        ASSERT_NEAR(got.rgb[i], expected.rgb[i], 1e-5 * std::max(std::abs(got.rgb[i]), std::abs(expected.rgb[i])) + 1e-7)
            << "isolated render vs pyramid buffer at value " << i;
    }
  // The Cornell box has no medium: no E buffer, whatever --medium-sampling says.
  const Scene box(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  EXPECT_FALSE(covers(RenderSession(box, s).pyramidFamilies(), TechniqueKind::Equiangular));
  EXPECT_FALSE(covers(pyramidFamilies(s, box), TechniqueKind::Equiangular));
  RenderSettings distance = s;
  distance.mediumSampling = MediumSampling::Distance;
  EXPECT_FALSE(covers(pyramidFamilies(distance, fog), TechniqueKind::Equiangular));
}

// E(1, t) runs on the camera walk's ray z(t-2) -> z(t-1): enabled alone at its length, with no
// connection asking for t camera vertices, it still makes the walk that long (it once did not,
// and the weights of (2,2) and (3,1), which count E(1,3), left its share out of the image).
TEST(EquiangularRender, AnEquiangularTechniqueAloneGetsTheWalkItNeeds) {
  const Scene fog(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/fog-lamp.gltf"));
  RenderSettings s;
  s.width = 16, s.height = 12, s.maxLength = 3, s.seed = 5;
  s.integrator = IntegratorKind::Bpt;
  s.mediumSampling = MediumSampling::Mis;
  s.techniques = TechniqueSet::parse("1,1;1,2;2,1;2,2;3,1;E1,3");  // no connection with t = 3
  RenderSession session(fog, s);
  session.renderPass();
  EXPECT_GT(session.counters().technique(Technique::equiangular(3)).contributed, 0u);
  EXPECT_EQ(session.counters().technique(Technique::equiangular(2)).tried, 0u);  // not enabled
}

}  // namespace
}  // namespace pathlab
