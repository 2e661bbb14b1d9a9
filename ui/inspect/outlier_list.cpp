// The outlier list's rows from the renderer's list, their replays, and opening one.
#include "ui/inspect/outlier_list.h"

#include "core/bpt/variance_aware_mis.h"
#include "core/render/outlier_replay.h"

#include <fmt/core.h>

#include <memory>

namespace pathlab::ui {

namespace {

bool sameOutlier(const Outlier& a, const Outlier& b) {
  return a.id.x == b.id.x && a.id.y == b.id.y && a.id.sample == b.id.sample &&
         a.technique.index() == b.technique.index() && a.luminance == b.luminance;
}

}  // namespace

std::string outlierFinderProblem(const RenderSettings& settings) {
  if (settings.integrator == IntegratorKind::Pt)
    return "the path tracer has no (s,t) techniques to rank: switch to bpt, lt, vcm, bpm or ppm";
  if (settings.integrator == IntegratorKind::Mlt)
    return "Metropolis samples are not independent: switch to bpt, lt, vcm, bpm or ppm to find outliers";
  return "";
}

std::string outlierRatioProblem(const OutlierList& list, const Outlier& o) {
  if (covers(enabledTechniques(list.settings).families(), TechniqueKind::Merge))
    return "with merges a replay traces its pass's every light subpath again: open the row to see its densities";
  if (list.settings.mis.heuristic == MisHeuristic::VarianceAware && o.id.sample >= kVarianceAwarePilotPasses)
    return fmt::format("variance-aware MIS weighs sample {} with factors a replay here does not have", o.id.sample);
  if (list.settings.lightPathsAuto && o.id.sample >= static_cast<uint64_t>(kLightPathPilotPasses))
    return fmt::format("--light-paths auto rendered sample {} at a light subpath count a replay here does not have",
                       o.id.sample);
  return "";
}

int replayOutlierRows(OutlierListState& state, const Scene& scene, int replays) {
  int done = 0;
  for (OutlierRow& row : state.rows) {
    if (done >= replays) break;
    if (row.replayed || !outlierRatioProblem(state.list, row.o).empty()) continue;
    if (!state.replayer || state.replayerScene != &scene || !(state.replayer->settings() == state.list.settings)) {
      state.replayer = std::make_shared<const RenderSession>(scene, state.list.settings);
      state.replayerScene = &scene;
    }
    const ReplayedOutlier r = replayOutlier(*state.replayer, row.o);
    row.replayed = true;
    row.densityRatio = r.densityRatio;
    row.best = r.best;
    ++done;
  }
  return done;
}

bool updateOutlierList(OutlierListState& state, const ProgressiveRenderer& renderer, const Scene& scene, int replays) {
  bool changed = false;
  OutlierList list;
  // A new generation publishes an empty list first: the rows shown stay (they still open, pinned to
  // their render) until it has rows of its own. Opening one resizes the image, and its list would
  // otherwise vanish under the click.
  if (!state.hold && renderer.outliers(list, state.version) && !(list.top.empty() && !state.rows.empty())) {
    std::vector<OutlierRow> rows;
    for (const Outlier& o : list.top) {
      OutlierRow row{o};
      // A row of the same generation seen before keeps its replay.
      if (list.generation == state.list.generation)
        for (const OutlierRow& old : state.rows)
          if (sameOutlier(old.o, o)) row = old;
      rows.push_back(row);
    }
    if (list.generation != state.list.generation) state.opened = -1;
    state.list = std::move(list);
    state.rows = std::move(rows);
    changed = true;
  }
  return replayOutlierRows(state, scene, replays) > 0 || changed;
}

void openOutlier(PathInspectorState& inspector, const Outlier& o, const RenderSettings& settings) {
  inspector.on = true;
  // The centre of its pixel: the fraction maps back to the same pixel (refreshInspection).
  inspector.pick = Vec2((static_cast<float>(o.id.x) + 0.5f) / static_cast<float>(settings.width),
                        (static_cast<float>(o.id.y) + 0.5f) / static_cast<float>(settings.height));
  inspector.sample = o.id.sample;
  inspector.focus = o;
  inspector.pinned = settings;
  inspector.pinnedShown.reset();
}

}  // namespace pathlab::ui
