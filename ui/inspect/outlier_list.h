// The viewer's outlier list (issue 34): the brightest weighted contributions of the image's
// generation, the fireflies, as `pathlab outliers` lists them, renewed after every full pass; a
// row opens its sample in the path inspector and the 3D view. No ImGui here: the state, its rows
// from the renderer's list, and what opening one does.
#pragma once

#include "core/render/progressive_renderer.h"
#include "ui/inspect/path_inspector.h"
#include "ui/viewer_options.h"  // kDefaultViewerOutliers, kMaxViewerOutliers

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pathlab::ui {


struct OutlierRow {
  Outlier o;
  // p / best (replayOutlier's density ratio) once a replay here gave it; `replayed` stays false
  // while the row waits for its replay, or when none is cheap or exact here (outlierRatioProblem).
  bool replayed = false;
  double densityRatio = 0.0;
  Technique best;
};

struct OutlierListState {
  bool on = false;
  int count = kDefaultViewerOutliers;  // rows kept
  bool markers = true;                 // each outlier marked where it landed on the image
  OutlierList list;                    // the renderer's newest
  uint64_t version = 0;                // ProgressiveRenderer::outliers
  std::vector<OutlierRow> rows;
  int opened = -1;  // the row last opened in the inspector (-1: none)
  // The rows are held (no newer list taken) while the inspector replays one of them with the
  // list's settings (PathInspectorState::pinned): exploring a list, row after row, is not undone
  // by the new generation that opening the inspector started. Set by the viewer every frame.
  bool hold = false;
  // The session rows are replayed in (its settings the list's, its scene `replayerScene`), kept
  // from one list to the next: making one allocates a film.
  std::shared_ptr<const RenderSession> replayer;
  const Scene* replayerScene = nullptr;
};

// Why the outlier finder cannot rank these settings' samples ("" when it can): the path tracer
// and Metropolis have no independent (s,t) samples.
std::string outlierFinderProblem(const RenderSettings& settings);
// Why p / best is not replayed here for a sample of `list` ("" when it is): merges trace the
// pass's every light subpath again for one replay, and variance-aware MIS weighs a sample after
// its pilot passes with factors a replay does not have.
std::string outlierRatioProblem(const OutlierList& list, const Outlier& o);

// Takes the renderer's newest list into `state` unless it holds its rows (keeping the replays of
// rows it had; an empty list keeps the rows there are, those of an earlier generation until the
// new one has its own), then replays
// at most `replays` rows still without p / best (the rest follow on later calls). Returns whether
// the rows changed.
bool updateOutlierList(OutlierListState& state, const ProgressiveRenderer& renderer, const Scene& scene,
                       int replays = 8);
// Replays the rows without p / best (up to `replays`); returns how many it replayed.
int replayOutlierRows(OutlierListState& state, const Scene& scene, int replays);

// The path inspector on `o`'s camera sample (its pixel, as a fraction of the image `settings`
// render, and its pass), replayed with `settings` (pinned) and selecting `o`'s own record.
void openOutlier(PathInspectorState& inspector, const Outlier& o, const RenderSettings& settings);

}  // namespace pathlab::ui
