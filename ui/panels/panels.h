// The viewer's panels as functions over the state they edit (ui/viewer_state.h). What a panel
// cannot do by editing its state (open a scene, save, load a reference, ...) it asks of the viewer
// through PanelRequests, which the viewer carries out after the panels are drawn. All between
// ImGui::NewFrame and ImGui::Render.
#pragma once

#include "ui/estimator/estimator_state.h"
#include "ui/estimator/technique_map_view.h"
#include "ui/input/shortcuts.h"
#include "ui/inspect/outlier_list.h"
#include "ui/inspect/path_inspector.h"
#include "ui/inspect/view3d.h"
#include "ui/lane/compare.h"
#include "ui/viewer_state.h"
#include "core/bpt/light_path_choice.h"
#include "core/mlt/metropolis.h"

#include <imgui.h>

#include <optional>
#include <string>
#include <vector>

namespace pathlab::ui {

struct PanelRequests {
  std::vector<Action> actions;  // as if their key had been pressed
  std::optional<std::string> openScene;
  std::optional<std::string> loadReference;
  std::optional<int> preset;
  bool rescanScenes = false;
  bool returnToReferenceView = false;
  bool exportErrorCsv = false;
  std::optional<std::string> compareConfig;  // side B's CONFIG typed in the compare section
  std::optional<int> openOutlier;            // a row of the outlier list clicked
};

// An area of the window in ImGui coordinates.
struct PanelRect {
  float x = 0.f, y = 0.f, width = 0.f, height = 0.f;
};

// Side panel sections (panel_side.cpp, panel_techniques.cpp, panel_reference.cpp).
// `warning`: the estimator's (estimatorWarning), shown in the warning colour when not empty.
void drawStatusSection(const RenderSnapshot& snapshot, const std::string& warning, RunState& run, double frameMs,
                       PanelRequests& requests);
// Integrator, maximum length, MIS, the combine / isolate mode and the technique grid; `counters`
// (of the shown image) for the cells' tooltips.
// `check`: the consistency check of the shown image (null when off): cells of techniques that
// disagree turn red, with the z-score in their tooltip.
// `shown`: the settings and passes of the shown image and the scene's bounding radius, for the
// radius its last merge pass used.
struct MergeRadiusNow {
  const RenderSettings* shown = nullptr;
  uint64_t passes = 0;
  float sceneRadius = 0.f;
};
void drawEstimatorSection(EstimatorState& estimator, TechniqueGridState& grid, const std::string& settingsError,
                          const Counters& counters, const CheckReport* check, const MltSummary* mlt,
                          const MergeRadiusNow& radiusNow, TechniqueFamilies sampled,
                          const LightPathStatus* lightPaths = nullptr);
void drawDisplaySection(DisplaySettings& display, RunState& run, PyramidView& pyramid, const Image& shown);
void drawSceneSection(SceneState& scene, bool cameraMoved, PanelRequests& requests);
void drawPresetSection(const PresetState& presets, PanelRequests& requests);
// The environment (panel_environment.cpp): a map's path, a uniform colour or none, its strength
// and rotation; edits `environment.edited`, which the viewer applies in the background.
void drawEnvironmentSection(EnvironmentState& environment);
// The path inspector (panel_inspector.cpp): its section of the side panel (on / off, the picked
// sample's techniques, the selected path under every technique) and its overlay over the image
// (origin and size in ImGui coordinates; `raster` the inspected image's size in pixels).
void drawInspectorSection(PathInspectorState& state, View3DState& view3d, PanelRequests& requests);
void drawInspectorOverlay(const InspectorOverlay& overlay, const PathInspectorState& state, ImVec2 origin, ImVec2 size,
                          Vec2i raster, float uiScale);
// The overlay's segments and markers, `raster` (its coordinates' extent) mapped onto origin, size.
void drawOverlayShapes(ImDrawList* draw, const InspectorOverlay& overlay, ImVec2 origin, ImVec2 size, Vec2i raster,
                       float uiScale);
// The picked sample's techniques and its selected path under every technique, in a window of its own
// at `rect` (below the image).
void drawInspectorWindow(PathInspectorState& state, PanelRect rect, PanelRequests& requests);
// The outliers section (panel_outliers.cpp): on / off, how many, the list (a click asks for the row's
// sample in the inspector: requests.openOutlier); `edited`: the settings the panels ask for, to
// say why the finder cannot run with them; `shown`: the image shown (is the list of its generation).
void drawOutlierSection(OutlierListState& state, const RenderSettings& edited, const RenderSnapshot& shown,
                        PanelRequests& requests);
// A ring where each outlier landed, numbered, over the image (origin and size in ImGui
// coordinates, `shown` its settings); nothing when the list's render is not of the same view and
// estimator (sameExceptSize).
void drawOutlierMarkers(const OutlierListState& state, ImVec2 origin, ImVec2 size, const RenderSettings& shown,
                        float uiScale);
// The 3D view (panel_view3d.cpp): the raster's texture (OpenGL's rows, bottom first) at origin,
// size, the overlay over it (its raster coordinates span `raster`) and a caption.
void drawView3DWindow(void* texture, const InspectorOverlay& overlay, ImVec2 origin, ImVec2 size, Vec2i raster,
                      const std::string& caption, float uiScale);
// The A/B comparison (panel_compare.cpp): on / off, side B's CONFIG, swap; `b`: B's shown image,
// `refused`: why B's renderer refused its last settings ("" when it took them).
void drawCompareSection(CompareState& compare, const RenderSnapshot& b, const std::string& refused,
                        PanelRequests& requests);
// `estimator` (its camera and lens) to offer a way back to the reference's view.
void drawReferenceSection(ReferenceState& reference, ConvergenceState& convergence, DisplaySettings& display,
                          const RenderSettings& edited, const Image& shown, PanelRequests& requests);

// The convergence panel along the bottom (panel_convergence.cpp): error plot and technique table.
float convergencePanelHeight(float windowHeight, float uiScale);
void drawConvergenceWindow(ConvergenceState& convergence, ReferenceState& reference, const RenderSnapshot& snapshot,
                           PanelRect rect, float uiScale, PanelRequests& requests);
// The per-technique table (core/metrics/technique_table.h) of the shown image, sortable.
void drawTechniqueTable(const RenderSnapshot& snapshot);

// The technique pyramid on the right (panel_pyramid.cpp). pyramidPanelWidth sets view.thumbnail
// and view.both for the space left of the window; a click on a thumbnail isolates its technique.
// imageAspect: the image's width / height when it has one of its own (the camera's); none: the
// image takes the room the panel leaves. merges: a row of merges below each length k >= 2;
// equiangular: E(1, k) at the end of each row.
float pyramidPanelWidth(PyramidView& view, int maxLength, float availableWidth, float height, float uiScale,
                        std::optional<float> imageAspect, bool merges, bool equiangular = false);
void drawPyramidWindow(PyramidView& view, const PyramidImages& images, EstimatorState& estimator, PanelRect rect,
                       float uiScale);

// panel_help.cpp: every shortcut; and the captions drawn over the image.
void drawHelpWindow(bool& show);
// What the captions over the image say.
struct ImageOverlay {
  ImVec2 origin, size;             // the image area, ImGui coordinates
  const RenderSnapshot* shown;     // the image shown (settings.width is 0 before the first)
  RenderSettings edited;           // the settings the panels ask for (renderSettings)
  DisplaySettings display;         // as the image is drawn: errorView only while the reference is valid
  std::string errorViewProblem;    // why the error view is not shown although asked for ("" otherwise)
  bool idleForNoTechnique = false, paused = false;
  float uiScale = 1.f;
  std::optional<Technique> zMap;  // the check's |z| per block over the image, for this technique
  std::string mapName;            // the technique map shown over the image (mapViewName), or ""
  std::string side;               // "A" or "B" while comparing (the caption names it), else ""
};
void drawImageOverlay(const ImageOverlay& overlay);
// The error view's colour bar with its scale, in the side panel (panel_reference.cpp).
void drawErrorBar(const DisplaySettings& display);
// The viridis colour scale as a horizontal bar of w x h pixels at `origin` (panel_reference.cpp).
void drawViridisBar(ImDrawList* draw, ImVec2 origin, float w, float h);
// The technique maps section (panel_maps.cpp): show them, choose the map, and its legend or colour
// bar. `maxLength` bounds the maps' length; `families`: whose techniques the maps hold (merges
// with vcm and bpm); `waiting` while no map has arrived yet.
void drawTechniqueMapSection(MapView& view, int maxLength, TechniqueFamilies families, bool waiting);
// The same, over the image's top right corner.
void drawErrorBarOverlay(const DisplaySettings& display, ImVec2 imageOrigin, ImVec2 imageSize, float uiScale);

}  // namespace pathlab::ui
