// Optimal MIS (Kondapaneni et al. 2019; core/bpt/optimal_mis.h). Tested: the solve; on a 1D integral
// whose optimal coefficients are computable by quadrature (its integrand zero on part of the domain,
// where the paper's normalised system and ours differ), the coefficients the passes estimate, the
// estimator's expectation and its variance against the closed form's and the balance heuristic's;
// the kernel's balance weights of every technique of a path against the inspector's; the image's
// unbiasedness on bundled scenes (agreement with the balance heuristic and the path tracer); the same
// image at any thread count is in render_reproducible_test.cpp, the refusals in render_settings_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <random>

#include "core/bpt/bidir_tracer.h"
#include "core/bpt/optimal_mis.h"
#include "core/render/render_session.h"
#include "core/render/render_settings.h"
#include "core/render/sample_outputs.h"
#include "tests/support/agreement.h"
#include "tests/support/test_scenes.h"

namespace pathlab {
namespace optimal_mis_test {

TEST(OptimalMis, SolvesTheSystemAndPinsTheRowsThatSawNothing) {
  // (M + diag(d)) beta = v with M = [[2, 1, 0], [1, 3, 0], [0, 0, 0]], d = (1, 0, 0): row 2 saw nothing.
  const std::array<double, 9> M{2, 1, 0, 1, 3, 0, 0, 0, 0};
  const std::array<double, 3> d{1, 0, 0};
  // Channel 0: v = A (1, 2) = (3 + 2, 1 + 6) = (5, 7); channels 1, 2: v = A (-1, 0.5).
  const std::array<double, 9> v{5, 7, 0, -3 + 0.5, -1 + 1.5, 0, -3 + 0.5, -1 + 1.5, 0};
  std::array<double, 9> beta{};
  ASSERT_TRUE(solveOptimalMis(3, M.data(), d.data(), v.data(), beta.data()));
  EXPECT_NEAR(beta[0], 1.0, 1e-9);
  EXPECT_NEAR(beta[1], 2.0, 1e-9);
  EXPECT_EQ(beta[2], 0.0);
  EXPECT_NEAR(beta[3], -1.0, 1e-9);
  EXPECT_NEAR(beta[4], 0.5, 1e-9);
  // A NaN in the sums: no coefficients (the balance heuristic), not NaN ones.
  std::array<double, 9> bad = M;
  bad[4] = std::nan("");
  EXPECT_FALSE(solveOptimalMis(3, bad.data(), d.data(), v.data(), beta.data()));
  for (const double b : beta) EXPECT_EQ(b, 0.0);
}

// A 1D integral over (0, 1) by two techniques, one sample of each per pass: p0 = 1 and p1 = 2x, f zero
// below 0.3. As a path of length 2 in a 1 x 1 image: technique s' = 0 is p0, s' = 1 is p1 (both camera
// techniques: one sample per pixel per pass), s' = 2 (light tracing) never contributes.
struct OneDimensional {
  static double f(double x) { return x > 0.3 ? 1.0 + 8.0 * (x - 0.3) * (x - 0.3) : 0.0; }
  static double p(int i, double x) { return i == 0 ? 1.0 : 2.0 * x; }
  static double sample(int i, double u) { return i == 0 ? u : std::sqrt(u); }
  static constexpr double kIntegral = 0.7 + 8.0 * 0.343 / 3.0;

  // Midpoint quadrature of g over (0, 1).
  static double quad(const std::function<double(double)>& g) {
    const int n = 200000;
    double sum = 0.0;
    for (int k = 0; k < n; ++k) sum += g((k + 0.5) / n);
    return sum / n;
  }
  // The closed form (optimal_mis.h): sum_k A_ik beta_k + (1 - c_i) beta_i = b_i (n_i = 1), or the paper's
  // A beta = b (normalised = true: c_i taken as 1).
  static std::array<double, 2> beta(bool normalised) {
    double A[2][2], b[2], c[2];
    for (int i = 0; i < 2; ++i) {
      for (int k = 0; k < 2; ++k)
        A[i][k] = quad([&](double x) { return f(x) != 0.0 ? p(i, x) * p(k, x) / (p(0, x) + p(1, x)) : 0.0; });
      b[i] = quad([&](double x) { return f(x) * p(i, x) / (p(0, x) + p(1, x)); });
      c[i] = normalised ? 1.0 : quad([&](double x) { return f(x) != 0.0 ? p(i, x) : 0.0; });
      A[i][i] += 1.0 - c[i];
    }
    const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
    return {(b[0] * A[1][1] - A[0][1] * b[1]) / det, (A[0][0] * b[1] - A[1][0] * b[0]) / det};
  }
  // The variance of one pass's estimate with coefficients beta (zero: the balance heuristic).
  static double variance(const std::array<double, 2>& beta) {
    double v = 0.0;
    for (int i = 0; i < 2; ++i) {
      auto g = [&](double x) {
        if (f(x) == 0.0) return 0.0;
        const double sum = p(0, x) + p(1, x);
        return beta[static_cast<size_t>(i)] + f(x) / sum - beta[0] * p(0, x) / sum - beta[1] * p(1, x) / sum;
      };
      const double m1 = quad([&](double x) { return g(x) * p(i, x); });
      const double m2 = quad([&](double x) { return g(x) * g(x) * p(i, x); });
      v += m2 - m1 * m1;
    }
    return v;
  }

  // Renders `passes` passes through OptimalMis; returns each pass's estimate of the integral. With
  // `roulette`, technique 0's sample survives with probability q(x) = 0.2 + 0.7 x and its contribution
  // is divided by q, as Russian roulette does to a walk; `scaleCorrection` passes 1 / q to OptimalMis.
  static std::vector<double> render(OptimalMis& optimal, int passes, std::mt19937_64& rng, bool roulette = false,
                                    bool scaleCorrection = true) {
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    OptimalMis::Splats splats;
    std::vector<double> estimates;
    const Vec2 pixel(0.5f, 0.5f);
    for (int pass = 0; pass < passes; ++pass) {
      double estimate = 0.0;
      for (int i = 0; i < 2; ++i) {
        const double x = sample(i, uniform(rng));
        const double q = roulette && i == 0 ? 0.2 + 0.7 * x : 1.0;
        if (q < 1.0 && uniform(rng) >= q) continue;
        if (f(x) == 0.0) continue;
        const double sum = p(0, x) + p(1, x);
        const double w[3] = {p(0, x) / sum, p(1, x) / sum, 0.0};
        const Spectrum C(static_cast<float>(f(x) / (sum * q)));
        const float scale = scaleCorrection ? static_cast<float>(1.0 / q) : 1.f;
        estimate += C.r + optimal.addCamera(i, 3, pixel, C, w, true, scale).r;
      }
      optimal.addSplats(splats, true);
      optimal.finishPass(true);
      estimates.push_back(estimate);
    }
    return estimates;
  }
};

OptimalMis oneByOne() { return OptimalMis(1, 1, {0}, 1, 2, 1.f, 1.0); }

// The coefficients the passes estimate are the closed form's, within the spread of 8 independent runs;
// the paper's normalised system, which ignores that the integrand vanishes below 0.3, has other ones.
TEST(OptimalMis, EstimatesTheClosedFormCoefficientsOfAOneDimensionalIntegral) {
  const std::array<double, 2> expected = OneDimensional::beta(false);
  const std::array<double, 2> normalised = OneDimensional::beta(true);
  const int runs = 8;
  std::array<double, 2> sum{}, sum2{};
  std::mt19937_64 rng(20261207);
  for (int r = 0; r < runs; ++r) {
    OptimalMis optimal = oneByOne();
    OneDimensional::render(optimal, 4000, rng);
    for (int i = 0; i < 2; ++i) {
      const double b = optimal.beta(0, i, 3).r;
      sum[static_cast<size_t>(i)] += b;
      sum2[static_cast<size_t>(i)] += b * b;
    }
    EXPECT_EQ(optimal.beta(0, 2, 3).r, 0.f);  // light tracing never contributed: no coefficient
  }
  for (size_t i = 0; i < 2; ++i) {
    const double mean = sum[i] / runs;
    const double se = std::sqrt(std::max((sum2[i] / runs - mean * mean) / (runs - 1), 0.0));
    EXPECT_NEAR(mean, expected[i], 4.0 * se + 1e-4) << "beta_" << i << " (standard error " << se << ")";
    EXPECT_GT(std::abs(normalised[i] - expected[i]), 20.0 * se) << "the test could not tell the two systems apart";
  }
}

// The estimate is unbiased while its coefficients move (passes from the first on), and once they have
// settled its variance is the closed form's optimum, below the balance heuristic's by the predicted factor
// (1.45 here); with the paper's normalised coefficients the variance would be twice the balance
// heuristic's (the closed form says so, which is why the solve keeps the 1 - c_i term).
TEST(OptimalMis, IsUnbiasedAndReachesTheOptimalVarianceOfAOneDimensionalIntegral) {
  const double optimum = OneDimensional::variance(OneDimensional::beta(false));
  const double balance = OneDimensional::variance({0.0, 0.0});
  EXPECT_GT(balance / optimum, 1.4);
  EXPECT_GT(OneDimensional::variance(OneDimensional::beta(true)), 1.5 * balance);
  std::mt19937_64 rng(7);
  OptimalMis optimal = oneByOne();
  const int passes = 200000, settled = 2000;
  const std::vector<double> estimates = OneDimensional::render(optimal, passes, rng);
  double sum = 0.0, sumLate = 0.0, sumLate2 = 0.0;
  for (int p = 0; p < passes; ++p) {
    sum += estimates[static_cast<size_t>(p)];
    if (p >= settled) {
      sumLate += estimates[static_cast<size_t>(p)];
      sumLate2 += estimates[static_cast<size_t>(p)] * estimates[static_cast<size_t>(p)];
    }
  }
  const double n = passes - settled;
  const double variance = (sumLate2 - sumLate * sumLate / n) / (n - 1.0);
  const double mean = sum / passes;
  EXPECT_NEAR(mean, OneDimensional::kIntegral, 4.0 * std::sqrt(balance / passes));
  // The sample variance of n values has a relative standard error of about sqrt(2 / n) (0.3 % here; the
  // estimates are not Gaussian, so 3 % is allowed).
  EXPECT_NEAR(variance / optimum, 1.0, 0.03) << "variance " << variance << ", optimum " << optimum;
  EXPECT_LT(variance, balance / 1.3);
}

// Russian roulette that spares one technique's samples and not the other's (the weights leave it out):
// scaled by the sample's 1 / q, as its contribution is, the correction keeps the estimate unbiased;
// unscaled it would not (the second render: 40 standard errors off).
TEST(OptimalMis, StaysUnbiasedWhenRouletteEndsOneTechniquesSamples) {
  const int passes = 100000;
  auto meanAndError = [&](bool scaled, uint64_t seed) {
    std::mt19937_64 rng(seed);
    OptimalMis optimal = oneByOne();
    const std::vector<double> e = OneDimensional::render(optimal, passes, rng, true, scaled);
    double sum = 0.0, sum2 = 0.0;
    for (const double x : e) sum += x, sum2 += x * x;
    const double mean = sum / passes;
    return std::pair{mean, std::sqrt((sum2 / passes - mean * mean) / passes)};
  };
  const auto [mean, error] = meanAndError(true, 11);
  EXPECT_NEAR(mean, OneDimensional::kIntegral, 4.0 * error);
  const auto [biased, biasedError] = meanAndError(false, 11);
  EXPECT_GT(std::abs(biased - OneDimensional::kIntegral), 10.0 * biasedError)
      << "unscaled corrections: the test could not tell " << biased << " from " << OneDimensional::kIntegral;
}

// The kernel's balance weights of every connection of a contributed path's length (what the corrections
// read) are the weights the inspector lists for the same path: checked in a sink that asks for both.
class BalanceWeightsSink final : public SampleSink {
 public:
  BalanceWeightsSink() : SampleSink(demand()) {}
  static SinkDemand demand() {
    SinkDemand d;
    d.everyContribution = true;
    d.onPath = true;
    d.balanceWeights = true;
    return d;
  }
  void record(const TechniqueResult& r) override {
    if (r.outcome != TechniqueOutcome::Contributed || !r.onPath) return;
    ASSERT_NE(r.balanceWeights, nullptr);
    double sum = 0.0;
    for (int sp = 0; sp < r.s + r.t; ++sp) {
      const TechniqueOnPath* y = findOnPath(*r.onPath, Technique{sp, r.s + r.t - sp});
      ASSERT_NE(y, nullptr);
      const double expected = y->counted ? y->balance : 0.0;
      EXPECT_NEAR(r.balanceWeights[sp], expected, 1e-6) << "(" << r.s << "," << r.t << ") slot " << sp;
      sum += r.balanceWeights[sp];
      between += r.balanceWeights[sp] > 0.01 && r.balanceWeights[sp] < 0.99 ? 1 : 0;
    }
    EXPECT_NEAR(sum, 1.0, 1e-6);
    ++checked;
    EXPECT_GT(r.omittedFactor, 0.f);
    maxOmitted = std::max(maxOmitted, r.omittedFactor);
    minOmitted = std::min(minOmitted, r.omittedFactor);
  }
  int checked = 0, between = 0;
  float maxOmitted = 0.f, minOmitted = 1e30f;

 private:
  bool splat(Vec2, const Spectrum&) override { return true; }
};

// `samples` camera samples of a 16 x 12 bpt render under optimal MIS of `scene` into a BalanceWeightsSink.
void sampleInto(BalanceWeightsSink& sink, const Scene& scene, bool roulette, int samples) {
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  s.maxLength = 6;
  s.integrator = IntegratorKind::Bpt;
  s.mis.heuristic = MisHeuristic::Optimal;
  s.russianRoulette = roulette;
  const Camera camera(scene.cameraDesc(), s.width, s.height);
  const BidirTracer tracer(scene, camera, bidirOptions(s));
  Counters counters;
  Pcg32 pixels(5, 9);
  for (int i = 0; i < samples; ++i) {
    const Vec2 pRaster(pixels.next1D() * static_cast<float>(s.width), pixels.next1D() * static_cast<float>(s.height));
    Pcg32 cameraRng(static_cast<uint64_t>(i), 1), lightRng(static_cast<uint64_t>(i), 2);
    tracer.sample(pRaster, pixels.next2D(), cameraRng, lightRng, sink, counters);
  }
}

TEST(OptimalMis, TheKernelsBalanceWeightsAreTheInspectorsOnEveryTechniqueOfThePath) {
  for (const char* name : {"cornell-box", "veach-mis", "fog"}) {
    BalanceWeightsSink sink;
    sampleInto(sink, test::bundledScene(name), true, 400);
    EXPECT_GT(sink.checked, 300) << name;
    EXPECT_GT(sink.between, sink.checked / 2) << name << ": weights strictly between 0 and 1, so the test can fail";
    // Russian roulette's 1 / q reaches the records (the correction's factor): some paths survived
    // a decision with q < 1.
    EXPECT_GT(sink.maxOmitted, 1.f) << name;
    EXPECT_GE(sink.minOmitted, 1.f) << name;
  }
}

// Without Russian roulette (and without delta vertices: cornell-box) no factor is left out of the
// densities: every record's factor is one.
TEST(OptimalMis, NothingIsLeftOutOfTheDensitiesWithoutRoulette) {
  BalanceWeightsSink sink;
  sampleInto(sink, test::bundledScene("cornell-box"), false, 200);
  EXPECT_GT(sink.checked, 100);
  EXPECT_EQ(sink.maxOmitted, 1.f);
  EXPECT_EQ(sink.minOmitted, 1.f);
}

// Unbiased on the bundled scenes: the optimal estimate agrees region by region with the balance
// heuristic's (other seeds) and with the path tracer's where it samples every path (as for variance-aware
// MIS, bpt_variance_aware_test.cpp).
void expectAgreement(test::BundledGroup group) {
  test::expectBundledGroupAgreement(
      group, "optimal", [](RenderSettings& s) { s.mis.heuristic = MisHeuristic::Optimal; }, 709);
}

TEST(OptimalMis, AgreesOnTheDiffuseScenes) { expectAgreement(test::BundledGroup::Diffuse); }

TEST(OptimalMis, AgreesOnTheGlossyAndSpecularScenes) { expectAgreement(test::BundledGroup::GlossyAndSpecular); }

// The group's scenes without media (it is refused in the others: IsRefusedInScenesWithMedia).
TEST(OptimalMis, AgreesInHardVisibility) {
  for (const test::BundledCase& c : {test::BundledCase{"door-ajar", 16, 12, 8, 2048, 0, 2},
                                     test::BundledCase{"many-lights", 15, 10, 6, 1024, 0, 2}})
    test::expectBundledAgreement(c, "optimal", [](RenderSettings& s) { s.mis.heuristic = MisHeuristic::Optimal; },
                                 709);
}

// Media put factors into a sample's throughput that its weights leave out and no sample knows
// (distance sampling, ratio tracking): the correction could not be scaled by them (optimal_mis.h).
TEST(OptimalMis, IsRefusedInScenesWithMedia) {
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.mis.heuristic = MisHeuristic::Optimal;
  for (const char* name : {"fog", "fog-lamp", "smoke"}) {
    const Scene scene = test::bundledScene(name);
    EXPECT_THROW(validateSettingsForScene(s, scene), std::invalid_argument) << name;
    // A session given them (the viewer's) renders the balance heuristic, and the status says why.
    EXPECT_EQ(RenderSession(scene, s).optimalMis(), nullptr) << name;
    EXPECT_FALSE(optimalMisWarning(scene, s).empty()) << name;
  }
  EXPECT_NO_THROW(validateSettingsForScene(s, test::bundledScene("cornell-box")));
}

}  // namespace optimal_mis_test
}  // namespace pathlab
