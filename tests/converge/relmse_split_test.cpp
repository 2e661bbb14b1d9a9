// The split of a convergence run's relMSE into squared bias and variance (issue 32; RelMseSplit in
// core/metrics/error_metrics.h): the parts sum to the relMSE of every checkpoint, the CSV carries
// them, and over independent seeds a consistent but biased estimator (vcm at a large fixed radius)
// shows a squared bias that bpt, unbiased, does not.
#include "core/converge/convergence.h"
#include "core/converge/convergence_config.h"
#include "core/converge/convergence_report.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

Scene splitTestBox() { return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf")); }

RenderSettings splitBase(uint64_t seed) {
  RenderSettings s;
  s.width = 24, s.height = 24, s.maxLength = 3, s.seed = seed;
  return s;
}

// bpt, many passes, a seed no configuration below uses.
Image splitReference(const Scene& scene, int passes) {
  RenderSettings s = splitBase(999);
  s.integrator = IntegratorKind::Bpt;
  RenderSession session(scene, s);
  for (int p = 0; p < passes; ++p) session.renderPass();
  return session.image();
}

ConvergenceCurve runSplitConfig(const Scene& scene, const std::string& config, uint64_t seed, const Image& reference,
                                uint64_t spp) {
  const ConvergenceConfig c = parseConvergenceConfigs(config, splitBase(seed)).front();
  ConvergenceBudget budget;
  budget.spp = spp;
  return runConvergence(scene, c, &reference, budget);
}

TEST(RelMseSplit, PartsSumToTheRelMseOfEveryCheckpoint) {
  const Scene scene = splitTestBox();
  const Image reference = splitReference(scene, 64);
  const ConvergenceCurve curve = runSplitConfig(scene, "vcm:radius=0.05,radius-alpha=1", 3, reference, 24);
  int split = 0;
  for (const Checkpoint& c : curve.checkpoints) {
    ASSERT_TRUE(c.error);
    if (c.spp < 2) {
      EXPECT_FALSE(c.split) << "one pass has no variance estimate";
      continue;
    }
    ASSERT_TRUE(c.split) << c.spp;
    EXPECT_EQ(c.split->relMse, c.error->relMse) << c.spp;
    EXPECT_NEAR(c.split->bias2 + c.split->variance, c.error->relMse, 1e-12 * c.error->relMse) << c.spp;
    EXPECT_GT(c.split->variance, 0.0);
    ++split;
  }
  EXPECT_GE(split, 3);
  const std::string csv = convergenceCsv({curve});
  EXPECT_NE(csv.find(",relmse_bias2,relmse_variance\n"), std::string::npos) << csv.substr(0, 200);
  EXPECT_NE(csv.find(fmt::format(",{:.6g},{:.6g}\n", curve.checkpoints.back().split->bias2,
                                 curve.checkpoints.back().split->variance)),
            std::string::npos);
}

struct SeedStats {
  double mean = 0.0, standardError = 0.0;
};
SeedStats overSeeds(const std::vector<double>& v) {
  double sum = 0.0, sum2 = 0.0;
  for (const double x : v) sum += x, sum2 += x * x;
  const double n = static_cast<double>(v.size()), mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, (sum2 - n * mean * mean) / (n - 1.0)) / n)};
}

// Over six seeds: bpt's squared bias is zero within its standard error over the seeds, up to the
// reference's own variance (which the split counts as bias, for every configuration alike); vcm
// at a fixed radius of 0.15 of the scene's size has a squared bias above bpt's by more than four
// standard errors of the difference, and at a quarter of that radius a smaller one.
TEST(RelMseSplit, ShowsTheBiasOfMergingAndNoneForBpt) {
  const Scene scene = splitTestBox();
  const Image reference = splitReference(scene, 4000);
  std::vector<double> bpt, vcmLarge, vcmSmall;
  double bptVariance = 0.0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    const RelMseSplit b = *runSplitConfig(scene, "bpt", seed, reference, 200).checkpoints.back().split;
    bpt.push_back(b.bias2);
    bptVariance += b.variance / 6.0;
    vcmLarge.push_back(runSplitConfig(scene, "vcm:radius=0.15,radius-alpha=1", seed, reference, 200).checkpoints.back().split->bias2);
    vcmSmall.push_back(runSplitConfig(scene, "vcm:radius=0.0375,radius-alpha=1", seed, reference, 200).checkpoints.back().split->bias2);
  }
  const SeedStats b = overSeeds(bpt), large = overSeeds(vcmLarge), small = overSeeds(vcmSmall);
  const std::string summary = fmt::format("bias2: bpt {:.3e} ± {:.1e}, vcm r=0.15 {:.3e} ± {:.1e}, vcm r=0.0375 {:.3e} ± {:.1e}",
                                          b.mean, b.standardError, large.mean, large.standardError, small.mean,
                                          small.standardError);
  // The reference's variance, 200 / 4000 of bpt's own, enters bpt's bias2 as about 5 % of its
  // variance part; allowed (twice) besides four standard errors over the seeds.
  EXPECT_LT(std::abs(b.mean), 4.0 * b.standardError + 0.1 * bptVariance) << summary << ", bpt variance " << bptVariance;
  EXPECT_GT(large.mean - b.mean, 4.0 * std::hypot(large.standardError, b.standardError)) << summary;
  EXPECT_LT(small.mean, large.mean - 2.0 * std::hypot(large.standardError, small.standardError)) << summary;
  std::cerr << summary << ", bpt variance " << bptVariance << "\n";
}

}  // namespace
}  // namespace pathlab
