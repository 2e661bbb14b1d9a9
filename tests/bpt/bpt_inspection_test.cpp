// The replayed sample the path inspector shows (`pathlab inspect`, issue 12): for random pixels and
// samples of every bundled scene under each heuristic, every technique's recorded path has s + t
// vertices from an emitter to the camera; the density of the path under every technique of its
// length multiplies out from the path's per-vertex densities (a zero, a delta, counting one); the
// weights under balance, power and uniform are recomputed from those densities and the "counted"
// flags alone; and the weight the renderer used for the sample equals the one for its heuristic.
#include "core/bpt/bidir_tracer.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>

namespace pathlab {
namespace {

double remapZero(double p) { return p == 0.0 ? 1.0 : p; }

// w_s from the listed densities: (n_s p_s)^b / sum over the counted techniques of (n p)^b, with n
// the light-tracing sample ratio for t = 1 (b = 1 balance, beta power); uniform 1 / count.
double recomputedWeight(const std::vector<TechniqueOnPath>& every, int s, MisHeuristic h, double beta) {
  const TechniqueOnPath& own = every[static_cast<size_t>(s)];
  if (!own.counted) return 0.0;
  int count = 0;
  double sum = 0.0;
  const double b = h == MisHeuristic::Power ? beta : 1.0;
  const auto n = [&](const TechniqueOnPath& x) { return x.t == 1 ? static_cast<double>(lightTracingRatio()) : 1.0; };
  for (const TechniqueOnPath& x : every)
    if (x.counted) {
      ++count;
      sum += std::pow(n(x) * x.pdfA / (n(own) * own.pdfA), b);
    }
  return h == MisHeuristic::Uniform ? 1.0 / count : 1.0 / sum;
}

void checkScene(const std::string& file, MisHeuristic heuristic) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + file));
  RenderSettings settings;
  settings.width = 48;
  settings.height = 36;
  settings.maxLength = 5;
  settings.integrator = IntegratorKind::Bpt;
  settings.mis.heuristic = heuristic;
  settings.seed = 5;
  const RenderSession session(scene, settings);
  Pcg32 rng(11, static_cast<uint64_t>(heuristic));
  int paths = 0, weighed = 0;
  // Samples until enough paths are checked (a scene with sky in view, many-lights, needs more).
  for (int i = 0; i < 400 && (i < 60 || paths <= 100 || weighed <= 30); ++i) {
    const int x = static_cast<int>(rng.next1D() * 48.f), y = static_cast<int>(rng.next1D() * 36.f);
    const uint64_t sample = rng.nextU32() % 1000;
    Counters counters;
    SampleTrace trace;
    session.replaySample(x, y, sample, counters, nullptr, &trace);
    ASSERT_EQ(trace.paths.size(), trace.records.size());
    ASSERT_EQ(trace.onPath.size(), trace.records.size());
    ASSERT_FALSE(trace.cameraSubpath.empty());
    EXPECT_EQ(trace.cameraSubpath[0].type, VertexType::Camera);
    if (!trace.lightSubpath.empty()) {
      EXPECT_EQ(trace.lightSubpath[0].type, VertexType::Light);
    }
    for (size_t r = 0; r < trace.records.size(); ++r) {
      const TechniqueResult& rec = trace.records[r];
      const TracedPath& path = trace.paths[r];
      if (path.size() == 0) continue;  // the technique formed no path
      const std::string where = file + " (" + std::to_string(rec.s) + "," + std::to_string(rec.t) + ") pixel " +
                                std::to_string(x) + "," + std::to_string(y) + " sample " + std::to_string(sample);
      ASSERT_EQ(static_cast<int>(path.size()), rec.s + rec.t) << where;
      // From an emitter (x0: a light vertex, or a surface on an area light for s = 0) to the lens.
      EXPECT_EQ(path.kind.back(), TracedVertexKind::Camera) << where;
      EXPECT_EQ(path.p.back(), trace.cameraSubpath[0].p) << where;  // a pinhole: the one lens point
      if (rec.s > 0) {
        EXPECT_EQ(path.kind.front(), TracedVertexKind::Light) << where;
      }
      const std::vector<TechniqueOnPath>& every = trace.onPath[r];
      ASSERT_EQ(every.size(), path.size()) << where;
      ++paths;
      for (const TechniqueOnPath& t : every) {
        if (!t.possible) {
          EXPECT_EQ(t.pdfA, 0.0) << where;
          continue;
        }
        double product = 1.0;
        for (size_t v = 0; v < path.size(); ++v)
          product *= remapZero(v == 0 && t.s == 1 ? path.x0Nee
                               : static_cast<int>(v) < t.s ? path.pFromLight[v]
                                                           : path.pFromCamera[v]);
        EXPECT_NEAR(t.pdfA, product, 1e-9 * product) << where << " under (" << t.s << "," << t.t << ")";
        for (const MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
          const double expected = recomputedWeight(every, t.s, h, settings.mis.beta);
          const double got = h == MisHeuristic::Balance ? t.balance : h == MisHeuristic::Power ? t.power : t.uniform;
          EXPECT_NEAR(got, expected, 1e-9 + 1e-6 * expected) << where << " " << misHeuristicName(h);
        }
      }
      // What the render used (the O(1) partial sums where they apply): the weight of the heuristic.
      if (rec.outcome == TechniqueOutcome::Contributed) {
        const TechniqueOnPath& own = every[static_cast<size_t>(rec.s)];
        const double expected = heuristic == MisHeuristic::Balance ? own.balance
                                : heuristic == MisHeuristic::Power ? own.power
                                                                   : own.uniform;
        EXPECT_NEAR(rec.weight, expected, 1e-5 * std::max(expected, 1e-3)) << where;
        ++weighed;
      }
    }
  }
  EXPECT_GT(paths, 100) << file;
  EXPECT_GT(weighed, 30) << file;
}

class Inspection : public testing::TestWithParam<std::tuple<std::string, MisHeuristic>> {};

TEST_P(Inspection, PathsDensitiesAndWeightsOfAReplayedSample) {
  checkScene(std::get<0>(GetParam()), std::get<1>(GetParam()));
}

INSTANTIATE_TEST_SUITE_P(BundledScenes, Inspection,
                         testing::Combine(testing::Values("cornell-box.gltf", "veach-mis.gltf", "caustic.gltf", "many-lights.gltf",
                                                          "bidir-lamp.gltf"),
                                          testing::Values(MisHeuristic::Balance, MisHeuristic::Power,
                                                          MisHeuristic::Uniform)));

}  // namespace
}  // namespace pathlab
