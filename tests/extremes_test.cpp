// Numerical extremes (issue 6): albedo near one with paths of up to 1000 edges, where throughput
// and density products over hundreds of vertices must neither overflow nor underflow, and
// Russian roulette must still reach the lengths that carry the answer.
#include "core/render/render_session.h"
#include "tests/support/statistics.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

// Every pixel of the furnace sees Le (1 - rho^K) / (1 - rho) at maximum length K. Per-pass
// image means (every pixel is one sample of the same value) give the standard error.
test::MeanEstimate furnaceMean(const Scene& scene, RenderSettings s, int passes) {
  RenderSession session(scene, s);
  test::RunningStats stats;
  double previous = 0.0;
  for (int pass = 1; pass <= passes; ++pass) {
    session.renderPass();
    double sum = 0.0;
    const Image img = session.image();
    for (size_t i = 0; i < img.rgb.size(); i += 3) sum += img.rgb[i];
    const double total = sum / static_cast<double>(img.width * img.height) * pass;
    stats.add(total - previous);
    previous = total;
  }
  EXPECT_EQ(session.counters().discarded(), 0u);
  return stats.estimate();
}

TEST(Extremes, AlbedoNearOneWithThousandEdgePaths) {
  const float rho = 0.999f, Le = 0.01f;
  const int K = 1000;
  const double expected = Le * (1.0 - std::pow(static_cast<double>(rho), K)) / (1.0 - rho);
  const Scene scene(test::furnace(rho, Le));
  struct Case {
    IntegratorKind integrator;
    const char* techniques;
    MisHeuristic heuristic;
  };
  // The full BPT connects every prefix pair: O(n^2) connections with O(n) weights each, about 1e9
  // operations a sample at n = 1000. The linear-cost subsets exercise the same long subpaths
  // and weights over 1000 vertices: path tracing with next-event estimation and light tracing.
  for (const Case& c : {Case{IntegratorKind::Pt, "all", MisHeuristic::Balance},
                        Case{IntegratorKind::Bpt, "s=0;s=1;t=1", MisHeuristic::Balance},
                        Case{IntegratorKind::Bpt, "s=0;s=1;t=1", MisHeuristic::Power},
                        Case{IntegratorKind::Bpt, "s=0;s=1", MisHeuristic::Uniform},
                        Case{IntegratorKind::Lt, "all", MisHeuristic::Balance}}) {
    RenderSettings s;
    s.width = s.height = 2;
    s.maxLength = K;
    s.seed = 77;
    s.integrator = c.integrator;
    s.techniques = c.techniques;
    s.mis.heuristic = c.heuristic;
    s.checkMis = c.integrator != IntegratorKind::Pt;
    const test::MeanEstimate m = furnaceMean(scene, s, 24);
    SCOPED_TRACE(testing::Message() << integratorName(c.integrator) << " " << c.techniques << " "
                                    << misHeuristicName(c.heuristic) << ": " << m.mean << " +- " << m.standardError
                                    << " expected " << expected);
    EXPECT_GT(m.standardError, 0.0);
    EXPECT_LT(std::abs(m.zScore(expected)), 4.5);  // 5 comparisons
    EXPECT_LT(m.standardError, 0.08 * expected);    // sharp enough to see a lost tail (0.95^1000)
  }
}

}  // namespace
}  // namespace pathlab
