// The viewer's path inspector (issue 12): the sample of a clicked pixel replayed exactly as the
// render computed it (core/render/sample_inspection.h) and drawn over the image through the render
// camera — the camera subpath, the light subpath, every (s,t) connection tried (blocked ones
// marked) and the selected technique's full path — with a table of the techniques and, for the
// selected one, its path under every technique of its length. Replaying never touches the
// renderer: nothing restarts. No ImGui or OpenGL here: state, replay and the overlay's geometry.
#pragma once

#include "core/camera/camera.h"
#include "core/render/outliers.h"
#include "core/render/render_settings.h"
#include "core/render/sample_inspection.h"
#include "core/scene/scene.h"

#include <optional>
#include <string>
#include <vector>

namespace pathlab::ui {

struct PathInspectorState {
  bool on = false;
  // Where the image was clicked, as a fraction of its width and height: the pixel under it in
  // whatever resolution the shown image has (a resize or a --render-scale change keeps the spot).
  std::optional<Vec2> pick;
  std::optional<Vec2i> pixel;  // the picked pixel of the inspected image (raster, from the top left)
  uint64_t sample = 0;         // its sample (pass) index
  int selected = -1;           // the highlighted technique: an index into the trace's records
  // An outlier to select when its sample is replayed (the outlier list's row opened), else the
  // technique that gave the sample most is; the next replay consumes it.
  std::optional<Outlier> focus;
  // The render an opened outlier came from: its sample replays with these settings rather than the
  // shown image's, since opening the inspector and the 3D view resizes the image (a new generation
  // whose pixels and passes are others). Released by a pick on the image, or when the shown
  // settings change in more than their size (pinnedShown: as they were when it was pinned).
  std::optional<RenderSettings> pinned, pinnedShown;
  std::optional<SampleInspection> result;
  // What `result` was replayed with: a change of the pixel, sample, settings or scene replays.
  std::optional<Vec2i> inspectedPixel;
  uint64_t inspectedSample = 0;
  RenderSettings inspectedSettings;
  const Scene* inspectedScene = nullptr;
  std::string error;  // why nothing can be inspected now ("" when it can)
};

// Replays the picked pixel's sample if anything it depends on changed (the path tracer has no
// techniques to show: `error` says so); returns whether it replayed. `shown`: the settings of the
// image shown, which the replay takes unless an outlier's are pinned; the pixel is the one under
// `pick` in the raster of the settings taken.
bool refreshInspection(PathInspectorState& state, const Scene& scene, const RenderSettings& shown);

// The sample of `pixel` among 0 .. n-1 that gave the most light (the luminance of its camera-side
// estimate plus its weighted t = 1 splats, wherever they land): a firefly hunt.
uint64_t brightestSample(const Scene& scene, const RenderSettings& settings, Vec2i pixel, uint64_t n);
// How many samples the brightest-sample search replays: 256, or 16 with merges (each of their
// samples traces its pass's every light subpath again, RenderSession::replaySample).
uint64_t brightestSearchCount(const RenderSettings& settings);

// Frustum and Particle: the 3D view's (ui/inspect/view3d.h). MergeDisk: the selected merge's disk
// of radius r about its camera vertex, in the surface's plane, and the step to its light vertex.
// ChainCurrent, ChainAccepted, ChainRejected: a Metropolis chain's current path, its last accepted
// moves and its rejected proposals (the 3D view's).
enum class SegmentRole {
  CameraSubpath, LightSubpath, Connection, BlockedConnection, Selected, Frustum, Particle, MergeDisk,
  ChainCurrent, ChainAccepted, ChainRejected
};
struct InspectorSegment {
  Vec2 a{0.f}, b{0.f};  // raster positions
  SegmentRole role = SegmentRole::Connection;
  // Particle: the throughput at its start, 0 (dim) .. 1 (the brightest); a chain's: its hue, 0 .. 1.
  float shade = 1.f;
};
struct InspectorMarker {
  Vec2 p{0.f};
  VertexType type = VertexType::Surface;
  bool delta = false;  // scattered by a delta lobe, or a point light / pinhole
  bool cameraSide = true;
};
struct InspectorOverlay {
  std::vector<InspectorSegment> segments;  // drawn in order: subpaths, connections, the selected path
  std::vector<InspectorMarker> markers;    // the subpaths' vertices
};

// The overlay of `state.result` in raster coordinates of `camera` (the render camera of the
// inspected settings): each segment clipped to the part in front of the lens (film-plane
// projection, so it may reach beyond the image; the drawing clips to the image). A selected merge
// adds its disk (mergeDiskPoints) and the step from its camera vertex to its light vertex.
InspectorOverlay inspectorOverlay(const PathInspectorState& state, const Camera& camera);
// Appends segment a -- b seen through `camera` (the part in front of the lens) to `overlay`.
void addOverlaySegment(InspectorOverlay& overlay, const Camera& camera, const Vec3& a, const Vec3& b, SegmentRole role,
                       float shade = 1.f);
// Where `camera` sees p (none behind the lens).
std::optional<Vec2> overlayPoint(const Camera& camera, const Vec3& p);
// The rim of a merge's disk: `n` points on the circle of radius r about the camera vertex, in the
// plane its normal sets (the density estimate's disk; the light vertex lies within r of its centre).
std::vector<Vec3> mergeDiskPoints(const MergedVertices& m, int n = 48);

}  // namespace pathlab::ui
