// The viewer's 3D view (issue 12): the scene from an orbit camera of its own — never the render's,
// so moving it restarts nothing — with the render camera's frustum, the punctual lights, the path
// inspector's sample (its subpaths, every connection tried, the selected full path) and the light
// particles, the last pass's light subpaths, drawn over it. The seed's first slides (light as
// particles travelling along polylines) in the actual scene.
//
// This file: the view's state and what it draws, in raster coordinates of its own camera. No
// OpenGL or ImGui: ui/gl/scene_raster.h draws the triangles, ui/panels/panel_view3d.cpp the rest.
#pragma once

#include "core/mlt/metropolis.h"
#include "core/render/light_subpath_replay.h"
#include "ui/inspect/path_inspector.h"
#include "ui/scene/orbit_camera.h"

#include <memory>
#include <optional>
#include <vector>

namespace pathlab::ui {

// The light subpaths of the newest pass for `count` pixels spread over the image (a fixed
// sequence per pass), replayed exactly as the render traced them (LightSubpathReplay).
struct LightParticles {
  static constexpr int kMaxCount = 1024;
  bool on = false;
  int count = 64;  // clamped to 1 .. kMaxCount where used
  std::vector<std::vector<PathVertex>> subpaths;
  // What `subpaths` were replayed for; a change replays.
  uint64_t pass = 0;
  int replayedCount = 0;
  std::shared_ptr<const Scene> scene;
  std::unique_ptr<LightSubpathReplay> replay;  // of `scene` with the shown image's settings
  std::string error;  // why there are none ("" when there are)
};

// A Metropolis render's watched chains (MltSummary::watched), drawn in place of the particles:
// each chain's current path thick, the pass's last accepted moves solid, its rejected proposals
// faint, a hue a chain.
struct ChainPaths {
  bool shown = false;  // the image shown is a Metropolis one: the particles' toggle draws these
  int count = 4;       // how many of the watched chains to draw (1 .. their number)
  bool rejected = true;
  std::shared_ptr<const MltSummary> summary;  // of the newest full pass
  uint64_t pass = 0;                          // its passes done
};

// The watched chains drawn: `count` of them spread evenly over the watched ones (which are spread
// over the chains, so over the lengths), indices into summary->watched.
std::vector<size_t> chainsShown(const ChainPaths& chains);

struct View3DState {
  bool on = false;
  // Faces turned away from the view are not drawn, so a closed room (the Cornell box) is seen into
  // from outside through its far side.
  bool cullBackFaces = true;
  std::optional<OrbitCamera> orbit;  // set for each scene the first time the view is shown
  const Scene* orbitScene = nullptr;
  LightParticles particles;
  ChainPaths chains;
};

// Sets the view's camera if it has none for `scene`: the render camera turned 35 degrees about the
// scene's centre and pulled back to 2.5 times its distance, so both the frustum and the scene show.
void ensureView3DCamera(View3DState& state, const Scene& scene, const CameraDesc& renderCamera);
// The view's camera for an area of `size` pixels (the orbit's pinhole, the area's aspect).
CameraDesc view3DCameraDesc(const View3DState& state);
Camera view3DCamera(const View3DState& state, Vec2i size);

// Near and far clipping distances along the view's axis that hold the scene's bounds (the near one
// small but never zero: the depth buffer's precision).
Vec2 view3DDepthRange(const Scene& scene, const CameraDesc& view);

// Replays the particles for the newest finished pass (`passes` done; none yet: nothing) when the
// pass, the settings, the scene or the count changed. Returns whether they changed. The path
// tracer traces no light subpaths: `error` says so.
bool refreshLightParticles(LightParticles& particles, const std::shared_ptr<const Scene>& scene,
                           const RenderSettings& settings, uint64_t passes);

// What the view draws over the triangles, in raster coordinates of `view`: the render camera's
// frustum (`shown`: the shown image's settings, its camera and size), the punctual lights as light
// markers, the particles (shade: the vertex's throughput, relative to the brightest, over three
// decades) or for a Metropolis image the chains' paths (shade: the chain's hue), then the
// inspector's sample as inspectorOverlay draws it over the image.
InspectorOverlay view3DOverlay(const View3DState& state, const PathInspectorState& inspector, const Scene& scene,
                               const RenderSettings& shown, const Camera& view);

// How the 3D view draws a material: a colour (linear RGB, alpha < 1 for see-through glass and
// blended surfaces) from its factors and its textures' averages; emitters in their emission's
// colour at full brightness, unshaded.
struct PreviewColour {
  Vec4 rgba{1.f};
  bool emitter = false;
};
// Every material's, in order; each texture is averaged once.
std::vector<PreviewColour> previewColours(const Scene& scene);

}  // namespace pathlab::ui
