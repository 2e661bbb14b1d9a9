// The viewer's outlier list (issue 34, ui/inspect/outlier_list.h) without a window: opening a row
// replays its sample with the settings of the render it came from (pinned), whatever size the
// image shown has since, selecting the outlier's own record; any other change releases the pin.
// Each row's p / best is replayOutlier's; rows whose replay is costly or inexact here get none. The
// rows never vanish when a new generation starts, and are held while one is open in the
// inspector. The script's outlier=K parses.
#include "ui/inspect/outlier_list.h"

#include "core/bpt/variance_aware_mis.h"
#include "core/render/outlier_replay.h"
#include "core/scene/gltf_loader.h"
#include "ui/input/input_script.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace pathlab::ui {
namespace {

const Scene& outlierScene() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  return scene;
}

RenderSettings outlierSettings() {
  RenderSettings s;
  s.width = 40;
  s.height = 30;
  s.maxLength = 6;
  s.seed = 11;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

OutlierList renderedList(const RenderSettings& s, uint64_t passes, int count) {
  RenderSession session(outlierScene(), s);
  session.setOutlierCount(count);
  for (uint64_t i = 0; i < passes; ++i) session.renderPass();
  return OutlierList{session.outliers(), 1, 0, passes, s};
}

TEST(OutlierList, AnOpenedRowReplaysItsSampleAtItsRenderWhateverTheShownSize) {
  const RenderSettings s = outlierSettings();
  const OutlierList list = renderedList(s, 6, 8);
  ASSERT_EQ(list.top.size(), 8u);
  // The image shown since: the same view at another size (the inspector's window took room).
  RenderSettings shown = s;
  shown.width = 53;
  shown.height = 39;
  for (const Outlier& o : list.top) {
    PathInspectorState state;
    openOutlier(state, o, s);
    ASSERT_TRUE(refreshInspection(state, outlierScene(), shown));
    ASSERT_TRUE(state.result.has_value()) << state.error;
    EXPECT_EQ(state.inspectedSettings, s);
    EXPECT_EQ(*state.pixel, Vec2i(o.id.x, o.id.y));
    EXPECT_EQ(state.result->sample, o.id.sample);
    ASSERT_GE(state.selected, 0);
    const TechniqueResult& r = state.result->trace.records[static_cast<size_t>(state.selected)];
    EXPECT_EQ(r.technique().index(), o.technique.index());
    EXPECT_NEAR(luminance(r.unweighted * r.imageWeight), o.luminance, 1e-5f * o.luminance);
    // Another change of the shown image than its size releases the pin: the shown image is inspected.
    RenderSettings power = shown;
    power.mis.heuristic = MisHeuristic::Power;
    ASSERT_TRUE(refreshInspection(state, outlierScene(), power));
    EXPECT_FALSE(state.pinned.has_value());
    EXPECT_EQ(state.inspectedSettings, power);
  }
}

TEST(OutlierList, EachRowsDensityRatioIsItsReplays) {
  OutlierListState state;
  state.list = renderedList(outlierSettings(), 6, 5);
  for (const Outlier& o : state.list.top) state.rows.push_back(OutlierRow{o});
  EXPECT_EQ(replayOutlierRows(state, outlierScene(), 2), 2);  // at most as many as asked
  EXPECT_EQ(replayOutlierRows(state, outlierScene(), 100), 3);
  const RenderSession session(outlierScene(), state.list.settings);
  for (const OutlierRow& row : state.rows) {
    ASSERT_TRUE(row.replayed);
    const ReplayedOutlier r = replayOutlier(session, row.o);
    EXPECT_EQ(row.densityRatio, r.densityRatio);
    EXPECT_GT(row.densityRatio, 0.0);
    EXPECT_LE(row.densityRatio, 1.0);
  }
}

TEST(OutlierList, NoReplayWhereItIsCostlyOrInexact) {
  OutlierList list;
  list.settings = outlierSettings();
  Outlier late;
  late.id.sample = kVarianceAwarePilotPasses;
  EXPECT_EQ(outlierRatioProblem(list, late), "");
  list.settings.mis.heuristic = MisHeuristic::VarianceAware;
  EXPECT_NE(outlierRatioProblem(list, late), "");
  Outlier pilot;
  pilot.id.sample = kVarianceAwarePilotPasses - 1;
  EXPECT_EQ(outlierRatioProblem(list, pilot), "");
  list.settings = outlierSettings();
  list.settings.techniques = TechniqueSet::parse("all;m=all");  // vcm
  EXPECT_NE(outlierRatioProblem(list, pilot), "");
  EXPECT_NE(outlierFinderProblem(RenderSettings{}), "");  // the path tracer, the default integrator
  RenderSettings mlt = outlierSettings();
  mlt.integrator = IntegratorKind::Mlt;
  EXPECT_NE(outlierFinderProblem(mlt), "");
  EXPECT_EQ(outlierFinderProblem(outlierSettings()), "");
}

TEST(OutlierList, RowsDoNotVanishWhenANewGenerationStarts) {
  auto scene = std::make_shared<const Scene>(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  ProgressiveRenderer renderer(scene, outlierSettings(), 2);
  renderer.setOutlierCount(4);
  OutlierListState state;
  for (int i = 0; i < 6000 && state.rows.empty(); ++i) {
    updateOutlierList(state, renderer, *scene);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_FALSE(state.rows.empty());
  const uint64_t first = state.list.generation;
  RenderSettings wider = outlierSettings();
  wider.width = 48;
  ASSERT_TRUE(renderer.setSettings(wider));
  for (int i = 0; i < 6000 && state.list.generation == first; ++i) {
    updateOutlierList(state, renderer, *scene);
    ASSERT_FALSE(state.rows.empty()) << "after " << i << " polls";
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(state.list.generation, renderer.generation());
  EXPECT_EQ(state.list.settings, wider);
  // Held (a row open in the inspector): the rows stay those of their generation.
  state.hold = true;
  RenderSettings wider2 = wider;
  wider2.width = 56;
  ASSERT_TRUE(renderer.setSettings(wider2));
  ASSERT_TRUE(renderer.waitForSpp(2, 60.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  updateOutlierList(state, renderer, *scene);
  EXPECT_EQ(state.list.settings, wider);
  state.hold = false;
  for (int i = 0; i < 6000 && state.list.settings != wider2; ++i) {
    updateOutlierList(state, renderer, *scene);
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(state.list.settings, wider2);
}

TEST(OutlierList, TheScriptOpensARow) {
  const std::vector<InputEvent> script = parseInputScript("3:outlier=2");
  ASSERT_EQ(script.size(), 1u);
  EXPECT_EQ(script[0].kind, InputEvent::Kind::Outlier);
  EXPECT_EQ(inputAt(script, 3).openOutlier, 2);
  EXPECT_FALSE(inputAt(script, 4).openOutlier.has_value());
  EXPECT_THROW(parseInputScript("3:outlier=0"), std::invalid_argument);
  EXPECT_THROW(parseInputScript("3:outlier=x"), std::invalid_argument);
}

}  // namespace
}  // namespace pathlab::ui
