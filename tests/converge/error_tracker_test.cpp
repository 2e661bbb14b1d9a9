// The viewer's live error measurement without the viewer: geometric checkpoints, one series per
// generation kept across generations (capped, clearable), a reference refused when it is broken
// and not compared when the view or size changed, and the observer of a real progressive renderer.
#include "core/converge/error_tracker.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pathlab {
namespace {

Image constantImage(int w, int h, float v) { return Image{w, h, std::vector<float>(3 * static_cast<size_t>(w * h), v)}; }

RenderSettings settingsOf(int w, int h) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  return s;
}

// Stands in for the progressive renderer's worker: one full pass of a generation.
void pass(ErrorTracker& tracker, uint64_t generation, const RenderSettings& s, const Scene* scene, uint64_t spp,
          double seconds, const Image& mean) {
  tracker.observe(PassInfo{generation, s, scene, spp, seconds}, mean);
}

TEST(CheckpointSchedule, FirstPassThenGeometricInTimeOrSamples) {
  CheckpointSchedule schedule(1.5);
  std::vector<uint64_t> recorded;
  // 1000 passes of 10 ms each.
  for (uint64_t spp = 1; spp <= 1000; ++spp) {
    const double seconds = 0.01 * static_cast<double>(spp);
    if (schedule.due(seconds, spp)) {
      schedule.record(seconds, spp);
      recorded.push_back(spp);
    }
  }
  ASSERT_FALSE(recorded.empty());
  EXPECT_EQ(recorded.front(), 1u);
  // Each checkpoint is the first pass past factor x the previous one: log_1.5(1000) = 17 of them.
  for (size_t i = 1; i < recorded.size(); ++i) {
    EXPECT_GE(static_cast<double>(recorded[i]), 1.5 * static_cast<double>(recorded[i - 1]) - 1e-9);
    EXPECT_LE(recorded[i], static_cast<uint64_t>(std::ceil(1.5 * static_cast<double>(recorded[i - 1]))));
  }
  EXPECT_EQ(recorded.size(), 16u);  // 1, 2, 3, 5, 8, 12, 18, ..., 473, 710
  // Samples grow faster than time (slow first pass): the samples alone make points due.
  CheckpointSchedule s2(2.0);
  s2.record(10.0, 1);
  EXPECT_FALSE(s2.due(11.0, 1));
  EXPECT_TRUE(s2.due(11.0, 2));
  EXPECT_TRUE(s2.due(20.0, 1));
  s2.reset();
  EXPECT_TRUE(s2.due(0.0, 0));
}

TEST(ErrorTracker, RefusesBrokenReferences) {
  ErrorTracker tracker;
  const ReferenceView view = viewOf(settingsOf(4, 2), nullptr);
  EXPECT_THROW(tracker.setReference(Image{}, view, "empty.exr"), std::invalid_argument);
  Image nan = constantImage(4, 2, 1.f);
  nan.rgb[5] = std::numeric_limits<float>::quiet_NaN();
  try {
    tracker.setReference(nan, view, "nan.exr");
    FAIL() << "a NaN reference was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("nan.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos) << e.what();
  }
  Image negative = constantImage(4, 2, 1.f);
  negative.rgb[0] = -1.f;
  EXPECT_THROW(tracker.setReference(negative, view, "negative.exr"), std::invalid_argument);
  EXPECT_EQ(tracker.reference(), nullptr);
}

TEST(ErrorTracker, SizeOrViewChangesStopTheComparison) {
  ErrorTracker tracker;
  const RenderSettings s = settingsOf(4, 2);
  int sceneA = 0, sceneB = 0;  // identities only
  const Scene* a = reinterpret_cast<const Scene*>(&sceneA);
  const Scene* b = reinterpret_cast<const Scene*>(&sceneB);
  EXPECT_EQ(tracker.statusFor(s, a), ReferenceStatus::None);
  tracker.setReference(constantImage(4, 2, 1.f), viewOf(s, a), "ref.exr");
  EXPECT_EQ(tracker.statusFor(s, a), ReferenceStatus::Valid);

  std::string why;
  EXPECT_EQ(tracker.statusFor(settingsOf(5, 2), a, &why), ReferenceStatus::SizeMismatch);
  EXPECT_NE(why.find("4 x 2"), std::string::npos) << why;
  EXPECT_NE(why.find("5 x 2"), std::string::npos) << why;
  RenderSettings moved = s;
  moved.camera = CameraDesc{};
  EXPECT_EQ(tracker.statusFor(moved, a, &why), ReferenceStatus::ViewChanged);
  EXPECT_NE(why.find("camera"), std::string::npos) << why;
  EXPECT_EQ(tracker.statusFor(s, b), ReferenceStatus::ViewChanged);
  // The estimator may differ: that is what is being compared.
  RenderSettings other = s;
  other.integrator = IntegratorKind::Bpt;
  other.maxLength = 3;
  EXPECT_EQ(tracker.statusFor(other, a), ReferenceStatus::Valid);

  // Passes of another size or view record nothing (no exception on the render thread either).
  pass(tracker, 1, settingsOf(5, 2), a, 1, 0.1, constantImage(5, 2, 2.f));
  pass(tracker, 2, moved, a, 1, 0.1, constantImage(4, 2, 2.f));
  EXPECT_TRUE(tracker.series().empty());
  pass(tracker, 3, other, a, 1, 0.1, constantImage(4, 2, 2.f));
  EXPECT_EQ(tracker.series().size(), 1u);
}

TEST(ErrorTracker, OneSeriesPerGenerationKeptAcrossChangesCappedAndCleared) {
  ErrorTracker tracker(3, 2.0);
  const RenderSettings s = settingsOf(2, 1);
  tracker.setReference(constantImage(2, 1, 1.f), viewOf(s, nullptr), "ref.exr");
  // Generation 1: the error halves each pass; checkpoints at 1, 2, 4, 8 passes.
  for (uint64_t spp = 1; spp <= 8; ++spp)
    pass(tracker, 1, s, nullptr, spp, 0.5 * static_cast<double>(spp), constantImage(2, 1, 1.f + 1.f / static_cast<float>(spp)));
  std::vector<ErrorSeries> series = tracker.series();
  ASSERT_EQ(series.size(), 1u);
  EXPECT_EQ(series[0].generation, 1u);
  EXPECT_EQ(series[0].label, seriesLabel(s));
  ASSERT_EQ(series[0].points.size(), 4u);
  EXPECT_EQ(series[0].points[2].spp, 4u);
  EXPECT_DOUBLE_EQ(series[0].points[2].seconds, 2.0);
  // Hand-computed: x = 1.25, r = 1 in every channel.
  EXPECT_NEAR(series[0].points[2].error.rmse, 0.25, 1e-6);
  EXPECT_NEAR(series[0].points[2].error.relMse, 0.0625 / 1.01, 1e-6);
  EXPECT_NEAR(series[0].points[2].error.mape, 0.25 / 1.01, 1e-6);

  // Another configuration: a second series, the first kept.
  RenderSettings power = s;
  power.integrator = IntegratorKind::Bpt;
  power.mis.heuristic = MisHeuristic::Power;
  pass(tracker, 2, power, nullptr, 1, 0.3, constantImage(2, 1, 3.f));
  series = tracker.series();
  ASSERT_EQ(series.size(), 2u);
  EXPECT_NE(series[0].label, series[1].label);
  EXPECT_LT(series[0].id, series[1].id);
  EXPECT_EQ(series[1].points.size(), 1u);

  // The cap drops the oldest.
  pass(tracker, 3, s, nullptr, 1, 0.3, constantImage(2, 1, 2.f));
  pass(tracker, 4, s, nullptr, 1, 0.3, constantImage(2, 1, 2.f));
  series = tracker.series();
  ASSERT_EQ(series.size(), 3u);
  EXPECT_EQ(series.front().generation, 2u);
  EXPECT_EQ(series.back().generation, 4u);

  // CSV: a header and one line per point.
  const std::string csv = tracker.csv();
  EXPECT_EQ(csv.rfind("series,label,generation,seconds,spp,rmse,relmse,mape\n", 0), 0u);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3);

  // Clear: the running generation goes on in a new series.
  const uint64_t before = tracker.version();
  tracker.clear();
  EXPECT_NE(tracker.version(), before);
  EXPECT_TRUE(tracker.series().empty());
  pass(tracker, 4, s, nullptr, 2, 0.6, constantImage(2, 1, 1.5f));
  series = tracker.series();
  ASSERT_EQ(series.size(), 1u);
  EXPECT_EQ(series[0].generation, 4u);
}

// The viewer's A/B comparison runs two renderers at once, each counting its own generations: their
// passes interleave, yet each lane keeps one series with its own checkpoints (issue 14), B's
// labelled as such, and the cap never drops a running series.
TEST(ErrorTracker, TwoRenderersAtOnceKeepASeriesEach) {
  ErrorTracker tracker(2, 2.0);
  const RenderSettings a = settingsOf(2, 1);
  RenderSettings b = a;
  b.integrator = IntegratorKind::Bpt;
  tracker.setReference(constantImage(2, 1, 1.f), viewOf(a, nullptr), "ref.exr");
  // Both renderers are in their generation 1; passes alternate.
  for (uint64_t spp = 1; spp <= 4; ++spp) {
    tracker.observe(PassInfo{1, a, nullptr, spp, 0.5 * static_cast<double>(spp)}, constantImage(2, 1, 2.f), 0);
    tracker.observe(PassInfo{1, b, nullptr, spp, 0.5 * static_cast<double>(spp)}, constantImage(2, 1, 3.f), 1);
  }
  std::vector<ErrorSeries> series = tracker.series();
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].label, seriesLabel(a));
  EXPECT_EQ(series[1].label, "B: " + seriesLabel(b));
  // Checkpoints at 1, 2 and 4 passes in each lane (factor 2), not thinned by the other's passes.
  ASSERT_EQ(series[0].points.size(), 3u);
  ASSERT_EQ(series[1].points.size(), 3u);
  EXPECT_NEAR(series[0].points[2].error.rmse, 1.0, 1e-6);
  EXPECT_NEAR(series[1].points[2].error.rmse, 2.0, 1e-6);
  // Side B restarts (its generation 2); the cap of 2 drops B's old series, never A's running one.
  tracker.observe(PassInfo{2, b, nullptr, 1, 0.5}, constantImage(2, 1, 3.f), 1);
  series = tracker.series();
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].label, seriesLabel(a));
  EXPECT_EQ(series[1].generation, 2u);
  EXPECT_EQ(series[1].points.size(), 1u);
  // A's next checkpoint (8 passes) still goes to its series.
  for (uint64_t spp = 5; spp <= 8; ++spp)
    tracker.observe(PassInfo{1, a, nullptr, spp, 0.5 * static_cast<double>(spp)}, constantImage(2, 1, 2.f), 0);
  EXPECT_EQ(tracker.series()[0].points.size(), 4u);
  // A lane that does not exist is ignored.
  tracker.observe(PassInfo{1, a, nullptr, 9, 9.0}, constantImage(2, 1, 2.f), kErrorLanes);
  EXPECT_EQ(tracker.series()[0].points.size(), 4u);
}

TEST(ErrorTracker, TheImageTakenAsReferenceIsNotComparedWithItself) {
  ErrorTracker tracker;
  const RenderSettings s = settingsOf(2, 1);
  tracker.setReference(constantImage(2, 1, 1.f), viewOf(s, nullptr), "generation 5", 5);
  pass(tracker, 5, s, nullptr, 64, 3.0, constantImage(2, 1, 1.f));
  EXPECT_TRUE(tracker.series().empty());
  pass(tracker, 6, s, nullptr, 1, 0.1, constantImage(2, 1, 2.f));
  EXPECT_EQ(tracker.series().size(), 1u);
  // A new reference starts a new comparison: the old series are not comparable with it.
  tracker.setReference(constantImage(2, 1, 2.f), viewOf(s, nullptr), "other.exr");
  EXPECT_TRUE(tracker.series().empty());
}

TEST(ErrorTracker, MetricsAndTheirMonteCarloRates) {
  ErrorMetrics m{4.0, 2.0, 0.5, 0.25};
  EXPECT_EQ(metricValue(m, ErrorMetric::RelMse), 0.5);
  EXPECT_EQ(metricValue(m, ErrorMetric::Rmse), 2.0);
  EXPECT_EQ(metricValue(m, ErrorMetric::Mape), 0.25);
  EXPECT_EQ(monteCarloSlope(ErrorMetric::RelMse), -1.0);
  EXPECT_EQ(monteCarloSlope(ErrorMetric::Rmse), -0.5);
  RenderSettings s;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse("s=0;s=1");
  s.maxLength = 6;
  EXPECT_EQ(seriesLabel(s), "bpt balance [s=0;s=1] L6");
  s.integrator = IntegratorKind::Lt;
  s.techniques = TechniqueSet::all();
  EXPECT_EQ(seriesLabel(s), "lt L6");
  s.integrator = IntegratorKind::Pt;
  s.russianRoulette = false;
  EXPECT_EQ(seriesLabel(s), "pt L6 no-RR");
  s.mediumSampling = MediumSampling::Distance;
  EXPECT_EQ(seriesLabel(s), "pt L6 no-RR media=distance");
}

// The observer of a real progressive renderer: points arrive from the render thread, error falls
// with samples, and render time excludes nothing but grows with the passes.
TEST(ErrorTracker, ObservesAProgressiveRenderer) {
  const auto scene = std::make_shared<const Scene>(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  RenderSettings s;
  s.width = 32;
  s.height = 24;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Pt;
  // The reference: many passes of the same view.
  RenderSession referenceSession(*scene, s);
  for (int i = 0; i < 256; ++i) referenceSession.renderPass();
  auto tracker = std::make_shared<ErrorTracker>(8, 1.5);
  tracker->setReference(referenceSession.image(), viewOf(s, scene.get()), "256 spp");

  RenderSettings measured = s;
  measured.seed = 7;  // independent samples
  ProgressiveRenderer renderer(scene, measured, 2);
  renderer.setPassObserver([tracker](const PassInfo& info, const Image& mean) { tracker->observe(info, mean); });
  // The worker started before the observer was there: measure a generation that starts after.
  measured.seed = 8;
  renderer.setSettings(measured);
  renderer.setTargetSpp(64);
  ASSERT_TRUE(renderer.waitForSpp(64, 120.0));
  const std::vector<ErrorSeries> series = tracker->series();
  ASSERT_FALSE(series.empty());
  ASSERT_EQ(series.back().generation, renderer.generation());
  const std::vector<ErrorPoint>& p = series.back().points;
  ASSERT_GE(p.size(), 5u);
  EXPECT_EQ(p.front().spp, 1u);
  for (size_t i = 1; i < p.size(); ++i) {
    EXPECT_GT(p[i].spp, p[i - 1].spp);
    EXPECT_GE(p[i].seconds, p[i - 1].seconds);
  }
  // relMSE falls about as 1/N (plus the reference's own 1/256): far below the first pass's.
  EXPECT_LT(p.back().error.relMse, 0.25 * p.front().error.relMse);
  RenderSnapshot snap;
  ASSERT_TRUE(renderer.snapshot(snap));
  EXPECT_GT(snap.renderSeconds, 0.0);
  EXPECT_LE(snap.renderSeconds, snap.seconds + 1e-9);
}

}  // namespace
}  // namespace pathlab
