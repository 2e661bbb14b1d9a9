// MIS off (Veach 1997, sec. 9.1, the naive combination): every enabled technique of length k
// weighs 1 / n_k whatever the path. Where every enabled technique can sample every path it is
// unbiased (the furnace, bpt_render_test.cpp); where some cannot, the estimate of a path x is
// f(x) c(x) / n_k with c(x) the techniques able to sample it. With a point light and no delta
// BSDF, s = 0 alone cannot sample any path, so with every technique enabled (n_k = k + 1)
//   E[off] = sum_k (1 - 1 / n_k) I_k = sum_k k / (k + 1) I_k,
// I_k the true image of length k (estimated here by the balance heuristic restricted to length k,
// which is unbiased: the other techniques of that length sample every path).
#include "core/bpt/bidir_tracer.h"
#include "core/bpt/mis_off.h"
#include "core/render/render_session.h"
#include "tests/support/bpt_scenes.h"
#include "tests/support/image_means.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

using test::MeanEstimate;
using test::passMeans;

using test::kMaxZ;

// The integrating sphere (no concave edge: every connection's geometry term is bounded, so the
// constant weights of the connections have a finite variance) lit by a point light instead of its
// emitting cap.
SceneDesc pointLitSphere() {
  SceneDesc desc = test::integratingSphere();
  desc.materials[1] = test::lambertian(0.7f);
  PunctualLightDesc light;
  light.type = PunctualLightType::Point;
  light.intensity = 4.f;
  light.position = Vec3(-0.6f, 0.9f, -0.4f);
  desc.punctualLights = {light};
  return desc;
}

RenderSettings sphereSettings(int maxLength, MisHeuristic h, const std::string& techniques, uint64_t seed) {
  RenderSettings s;
  s.width = s.height = 12;
  s.maxLength = maxLength;
  s.integrator = IntegratorKind::Bpt;
  s.mis.heuristic = h;
  s.techniques = TechniqueSet::parse(techniques);
  s.seed = seed;
  return s;
}

TEST(MisOff, WeightTableIsOneOverTheEnabledCountOfEachLength) {
  const std::vector<float> all = misOffWeights(TechniqueSet::all(), 4);
  ASSERT_EQ(all.size(), 5u);
  for (int k = 1; k <= 4; ++k) EXPECT_FLOAT_EQ(all[static_cast<size_t>(k)], 1.f / static_cast<float>(k + 1));
  // s <= 1 and (2, 1): n_1 = 2 ((0,2), (1,1)), n_2 = 3 ((0,3), (1,2), (2,1)), n_3 = 2.
  const std::vector<float> some = misOffWeights(TechniqueSet::parse("s=0;s=1;2,1"), 3);
  EXPECT_FLOAT_EQ(some[1], 0.5f);
  EXPECT_FLOAT_EQ(some[2], 1.f / 3.f);
  EXPECT_FLOAT_EQ(some[3], 0.5f);
  EXPECT_FLOAT_EQ(misOffWeights(TechniqueSet::parse("k=2"), 3)[1], 0.f);
}

// Off never takes the partial sums (they weigh by densities); the others keep their choice.
TEST(MisOff, TracerUsesTheTableNotThePartialSums) {
  Scene scene(pointLitSphere());
  const Camera camera(scene.cameraDesc(), 8, 8);
  BidirOptions o;
  o.maxLength = 5;
  o.techniques = TechniqueSet::all();
  o.mis.heuristic = MisHeuristic::Off;
  EXPECT_EQ(BidirTracer(scene, camera, o).misEvaluation(), MisEvaluation::Constant);
  o.mis.heuristic = MisHeuristic::Uniform;
  EXPECT_EQ(BidirTracer(scene, camera, o).misEvaluation(), MisEvaluation::PartialSums);
}

TEST(MisOff, BiasReportNamesTheLengthsAndTheReasons) {
  // Area light, no delta BSDF: unbiased, no warning.
  {
    Scene scene(test::furnace(0.5f, 1.f));
    EXPECT_FALSE(misOffBias(scene, TechniqueSet::all(), 6, true).biased());
    EXPECT_EQ(misOffWarning(misOffBias(scene, TechniqueSet::all(), 6, true)), "");
  }
  // Point light: every length where s = 0 is enabled beside another technique.
  {
    Scene scene(pointLitSphere());
    const MisOffBias all = misOffBias(scene, TechniqueSet::all(), 10, true);
    EXPECT_EQ(all.lengths, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
    const std::string w = misOffWarning(all);
    EXPECT_NE(w.find("lengths 1-10 biased"), std::string::npos) << w;
    EXPECT_NE(w.find("s = 0 cannot hit the point light (delta): lengths 1-10"), std::string::npos) << w;
    EXPECT_NE(w.find("no t = 0 technique"), std::string::npos) << w;
    // Without s = 0, or with s = 0 alone at a length, nothing is split.
    EXPECT_FALSE(misOffBias(scene, TechniqueSet::parse("s=1;s=2;t=1"), 10, true).biased());
    EXPECT_EQ(misOffBias(scene, TechniqueSet::parse("0,2;0,3;1,2;0,4"), 3, false).lengths, (std::vector<int>{2}));
  }
  // Area light with a mirror and glass: lengths >= 2, at a delta vertex.
  {
    Scene scene(test::deltaScene(test::DeltaLight::Area));
    const MisOffBias b = misOffBias(scene, TechniqueSet::all(), 5, true);
    EXPECT_EQ(b.lengths, (std::vector<int>{2, 3, 4, 5}));
    EXPECT_NE(misOffWarning(b).find("delta-BSDF vertex"), std::string::npos) << misOffWarning(b);
    // Path tracing's two techniques: at x1 delta, s = 1 cannot connect but s = 0 can.
    EXPECT_EQ(misOffBias(scene, TechniqueSet::pathTracing(), 5, true).lengths, (std::vector<int>{2, 3, 4, 5}));
    // s = 0 alone: nothing to split.
    EXPECT_FALSE(misOffBias(scene, TechniqueSet::withS(0), 5, true).biased());
  }
  // bpt's equiangular techniques (issue 35): E(1, k) counts wherever it is enabled, k >= 2, and
  // samples only paths through a medium. The area-lit furnace is otherwise unbiased.
  {
    Scene scene(test::furnace(0.5f, 1.f));
    const MisOffBias b = misOffBias(scene, TechniqueSet::parse("s=0;s=2;1,3;E1,3;1,4;E1,4"), 5, true, false, MediumSampling::Mis);
    EXPECT_EQ(b.lengths, (std::vector<int>{3, 4}));
    EXPECT_NE(misOffWarning(b).find("E(1,k) samples only paths whose vertex next to the light is in a homogeneous "
                                    "scattering medium: lengths 3-4"),
              std::string::npos)
        << misOffWarning(b);
    EXPECT_FALSE(misOffBias(scene, TechniqueSet::all(), 5, true, false, MediumSampling::Distance).biased());
    // Without E(1, k) in the set nothing counts it, C(1, k) enabled or not.
    EXPECT_FALSE(misOffBias(scene, TechniqueSet::parse("s=0;s=2;1,3;1,4"), 5, true, false, MediumSampling::Mis).biased());
  }
}

// The predicted bias of a point light: E[off] = sum_k k / (k + 1) I_k (see the top of the file).
// The negative control: off differs from the unbiased image by far more than the noise.
TEST(MisOff, PointLightLosesTheShareOfTheTechniqueThatCannotHitIt) {
  Scene scene(pointLitSphere());
  const int K = 3, passes = 64;
  const MeanEstimate off = passMeans(scene, sphereSettings(K, MisHeuristic::Off, "all", 31), passes);
  const MeanEstimate balance = passMeans(scene, sphereSettings(K, MisHeuristic::Balance, "all", 32), passes);
  double expected = 0.0, variance = 0.0;
  for (int k = 1; k <= K; ++k) {
    const MeanEstimate length =
        passMeans(scene, sphereSettings(K, MisHeuristic::Balance, "k=" + std::to_string(k), 40 + k), passes);
    const double share = static_cast<double>(k) / (k + 1);
    expected += share * length.mean;
    variance += share * share * length.standardError * length.standardError;
    std::cout << "length " << k << ": " << length.mean << " +- " << length.standardError << "\n";
  }
  const double se = std::sqrt(off.standardError * off.standardError + variance);
  const double z = (off.mean - expected) / se;
  std::cout << "off " << off.mean << " +- " << off.standardError << ", predicted " << expected << " +- "
            << std::sqrt(variance) << " (z " << z << "), balance " << balance.mean << " +- " << balance.standardError
            << "\n";
  EXPECT_LT(std::abs(z), kMaxZ);
  EXPECT_LT(se, 0.02 * expected);  // power: a 10% error in the prediction would be z > 5
  EXPECT_GT(std::abs(test::zDifference(off, balance)), 5.0 * kMaxZ);
}

}  // namespace
}  // namespace pathlab
