// A convergence run split over processes (CheckpointExchange), here played by threads that meet at
// a barrier, as `mpirun -n N pathlab converge` ranks meet in MPI collectives: with a sample budget
// it is the run of one process; with a time budget its checkpoints hold whole passes of every one.
#include "core/converge/checkpoint_exchange.h"
#include "core/converge/convergence.h"
#include "core/converge/convergence_report.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <barrier>
#include <cmath>
#include <thread>

namespace pathlab {
namespace {

const std::string kSplitScene = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

// Processes played by threads: each has an exchange; they meet at one barrier.
class ThreadProcesses {
 public:
  explicit ThreadProcesses(int n) : n_(n), barrier_(n), progress_(static_cast<size_t>(n)), sums_(static_cast<size_t>(n)) {}

  class Exchange : public CheckpointExchange {
   public:
    Exchange(ThreadProcesses& all, int rank) : all_(all), rank_(rank) {}
    int processes() const override { return all_.n_; }
    bool leader() const override { return rank_ == 0; }
    PassSchedule passSchedule() const override {
      return PassSchedule{static_cast<uint64_t>(rank_), static_cast<uint64_t>(all_.n_)};
    }
    std::vector<RunProgress> gatherProgress(const RunProgress& own) override {
      all_.progress_[static_cast<size_t>(rank_)] = own;
      all_.barrier_.arrive_and_wait();
      std::vector<RunProgress> every = all_.progress_;
      all_.barrier_.arrive_and_wait();
      return every;
    }
    void sumToLeader(std::span<const double> own, std::span<double> total) override {
      all_.sums_[static_cast<size_t>(rank_)] = own;
      all_.barrier_.arrive_and_wait();
      if (leader())
        for (size_t i = 0; i < total.size(); ++i) {
          total[i] = 0.0;
          for (std::span<const double> s : all_.sums_) total[i] += s[i];
        }
      all_.barrier_.arrive_and_wait();
    }

   private:
    ThreadProcesses& all_;
    int rank_;
  };

  // Runs `config` on every process at once; returns the leader's curve.
  ConvergenceCurve run(const Scene& scene, const ConvergenceConfig& config, const Image* reference,
                       const ConvergenceBudget& budget) {
    std::vector<ConvergenceCurve> curves(static_cast<size_t>(n_));
    std::vector<std::thread> threads;
    for (int r = 0; r < n_; ++r)
      threads.emplace_back([&, r] {
        Exchange exchange(*this, r);
        curves[static_cast<size_t>(r)] =
            runConvergence(scene, config, r == 0 ? reference : nullptr, budget, {}, nullptr, &exchange);
      });
    for (std::thread& t : threads) t.join();
    return curves[0];
  }

 private:
  int n_;
  std::barrier<> barrier_;
  std::vector<RunProgress> progress_;
  std::vector<std::span<const double>> sums_;
};

// The same samples summed in another order: 1e-6 relative (float read-outs of double sums).
void expectSameToRounding(double a, double b, const std::string& what, double relative = 1e-6) {
  EXPECT_LE(std::abs(a - b), relative * std::max(std::abs(a), std::abs(b)) + 1e-15)
      << what << ": " << a << " against " << b;
}
// The two-buffer estimate takes each pass's image from consecutive float running means of a
// process's own passes (EvenOddBuffers::addRunningMean): exact to about n · 6e-8 of a pixel value
// m after n passes, so process and processes differ there. The estimate squares A − B, about
// 2σ/√n: relative 2 · n · 6e-8 · m / |A − B|, some 2e-5 here (n = 13, m ≈ 0.5, |A − B| ≈ 0.04).
constexpr double kTwoBufferRelative = 1e-4;

TEST(ConvergenceSplit, ThreeProcessesWithASampleBudgetRunTheRunOfOne) {
  Scene scene(loadGltf(kSplitScene));
  RenderSettings base;
  base.width = 12;
  base.height = 8;
  base.maxLength = 4;
  ConvergenceBudget refBudget;
  refBudget.spp = 64;
  const Image reference = runConvergence(scene, {"ref", base}, nullptr, refBudget).image;
  ConvergenceBudget budget;
  budget.spp = 13;  // checkpoints 1, 2, 3, 5, 8, 12, 13: shares of 0 to 5 passes
  ThreadProcesses three(3);
  std::vector<ConvergenceCurve> curves;
  for (const ConvergenceConfig& config : parseConvergenceConfigs("bpt;pt", base)) {
    const ConvergenceCurve one = runConvergence(scene, config, &reference, budget);
    const ConvergenceCurve split = three.run(scene, config, &reference, budget);
    EXPECT_EQ(split.processes, 3);
    ASSERT_EQ(one.checkpoints.size(), split.checkpoints.size()) << config.label;
    for (size_t i = 0; i < one.checkpoints.size(); ++i) {
      const Checkpoint &a = one.checkpoints[i], &b = split.checkpoints[i];
      const std::string what = config.label + " at " + std::to_string(a.spp) + " spp";
      EXPECT_EQ(a.spp, b.spp) << what;
      EXPECT_EQ(a.cameraSamples, b.cameraSamples) << what;
      EXPECT_EQ(a.rays, b.rays) << what;
      ASSERT_TRUE(a.error && b.error) << what;
      expectSameToRounding(a.error->relMse, b.error->relMse, what + ", relMSE");
      expectSameToRounding(a.error->mape, b.error->mape, what + ", MAPE");
      expectSameToRounding(a.twoBuffer.mse, b.twoBuffer.mse, what + ", two-buffer MSE", kTwoBufferRelative);
    }
    ASSERT_EQ(one.image.rgb.size(), split.image.rgb.size());
    for (size_t i = 0; i < one.image.rgb.size(); ++i) expectSameToRounding(one.image.rgb[i], split.image.rgb[i], "pixel value");
    curves.push_back(split);
  }
  const std::string csv = convergenceCsv(curves);
  EXPECT_TRUE(csv.substr(0, csv.find('\n')).ends_with(",ranks")) << csv;
  EXPECT_TRUE(csv.ends_with(",3\n")) << csv;
}

TEST(ConvergenceSplit, WithATimeBudgetEveryCheckpointHoldsWholePassesOfEveryProcess) {
  Scene scene(loadGltf(kSplitScene));
  RenderSettings base;
  base.width = base.height = 6;
  base.integrator = IntegratorKind::Pt;
  ConvergenceBudget budget;
  budget.seconds = 0.05;
  ThreadProcesses two(2);
  const ConvergenceCurve curve = two.run(scene, {"pt", base}, nullptr, budget);
  ASSERT_GE(curve.checkpoints.size(), 2u);
  EXPECT_EQ(curve.checkpoints.front().spp, 2u);  // one pass each
  for (size_t i = 0; i < curve.checkpoints.size(); ++i) {
    const Checkpoint& c = curve.checkpoints[i];
    EXPECT_EQ(c.cameraSamples, c.spp * 36u);
    if (i > 0) {
      EXPECT_GE(c.spp, curve.checkpoints[i - 1].spp + 2);
    }
  }
  EXPECT_GE(curve.checkpoints.back().seconds, 0.05);
  EXPECT_GT(curve.checkpoints.back().twoBuffer.relMse, 0.0);
}

}  // namespace
}  // namespace pathlab
