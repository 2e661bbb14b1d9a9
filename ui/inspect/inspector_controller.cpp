// The path inspector and the 3D view carried out: replay, overlays, raster, export.
#include "ui/inspect/inspector_controller.h"

#include "core/render/inspection_report.h"
#include "ui/record/output_names.h"

#include <fmt/core.h>

namespace pathlab::ui {

PixelRect InspectorController::placeWindow(PixelRect room, bool showUi, float uiScale, float framebufferScale) {
  window_ = {};
  if (!showUi || !inspector.on) return room;
  const int h = std::min(static_cast<int>(0.42f * static_cast<float>(room.size.y)),
                         static_cast<int>(340.f * uiScale * framebufferScale));
  room.size.y -= h;
  window_ = {static_cast<float>(room.origin.x) / framebufferScale,
             static_cast<float>(room.origin.y + room.size.y) / framebufferScale,
             static_cast<float>(room.size.x) / framebufferScale, static_cast<float>(h) / framebufferScale};
  return room;
}

void InspectorController::drawWindow(PanelRequests& requests) {
  if (window_.height > 0.f) drawInspectorWindow(inspector, window_, requests);
}

void InspectorController::update(const std::shared_ptr<const Scene>& scene, const RenderSettings& shown,
                                 const RenderSnapshot& snapshot, const CameraDesc& camera) {
  // The inspected image is the one shown: its settings (size, camera, estimator) once one arrived.
  // The selected technique's path (and a merge's disk) is part of the overlay: a new selection
  // redraws it without replaying.
  if (refreshInspection(inspector, *scene, shown) || inspector.selected != overlaySelected_) {
    overlaySelected_ = inspector.selected;
    overlay_ = InspectorOverlay{};
    if (inspector.result) {
      const RenderSettings& s = inspector.inspectedSettings;
      overlay_ = inspectorOverlay(inspector, Camera(s.camera.value_or(scene->cameraDesc()), s.width, s.height, s.lens));
    }
  }
  if (!view3d.on) {
    // Its copy of the meshes and its scene go with it, once no frame draws its texture.
    if (!textureInUse_) raster_.reset();
    view3d.particles.replay.reset();
    view3d.particles.scene.reset();
    return;
  }
  if (!raster_) raster_ = std::make_unique<SceneRaster>();
  ensureView3DCamera(view3d, *scene, camera);
  // The particles (a Metropolis image: its chains) follow the newest full pass of the image shown.
  if (!snapshot.preview && snapshot.settings.width > 0) {
    refreshLightParticles(view3d.particles, scene, snapshot.settings, snapshot.samplesPerPixel);
    view3d.chains.shown = snapshot.settings.integrator == IntegratorKind::Mlt;
    view3d.chains.summary = view3d.chains.shown ? snapshot.mlt : nullptr;
    view3d.chains.pass = snapshot.samplesPerPixel;
  }
}

namespace {

std::string chainsCaption(const ChainPaths& chains) {
  const std::vector<size_t> shown = chainsShown(chains);
  if (shown.empty()) return "\nno Metropolis chains yet (L)";
  const size_t n = shown.size();
  std::string lengths;
  for (const size_t i : shown) {
    const MltWatchedChain& w = chains.summary->watched[i];
    if (w.length > 0) lengths += fmt::format("{}{}", lengths.empty() ? " (path lengths " : ", ", w.length);
  }
  if (!lengths.empty()) lengths += ")";
  return fmt::format("\n{} Metropolis chains after pass {}{} (L)\nthick: where each is; solid: its last accepted "
                     "moves{}",
                     n, chains.pass, lengths, chains.rejected ? ";\nfaint: its rejected proposals" : "");
}

}  // namespace

void InspectorController::drawOverlays(const Scene& scene, const RenderSettings& shown, ImVec2 imageOrigin,
                                       ImVec2 imageSize, float framebufferScale, float uiScale) {
  drawInspectorOverlay(overlay_, inspector, imageOrigin, imageSize,
                       {inspector.inspectedSettings.width, inspector.inspectedSettings.height}, uiScale);
  const PixelRect& r = view3dRect;
  textureInUse_ = view3d.on && raster_ && view3d.orbit && r.size.x > 0 && r.size.y > 0;
  if (!textureInUse_) return;
  const float s = framebufferScale;
  const ImVec2 origin(static_cast<float>(r.origin.x) / s, static_cast<float>(r.origin.y) / s);
  const ImVec2 size(static_cast<float>(r.size.x) / s, static_cast<float>(r.size.y) / s);
  const Camera view = view3DCamera(view3d, r.size);
  std::string caption = "3D view: drag orbits, Shift+drag pans, wheel zooms (O hides it)";
  if (view3d.particles.on && view3d.chains.shown)
    caption += chainsCaption(view3d.chains);
  else if (view3d.particles.on)
    caption += view3d.particles.error.empty()
                   ? fmt::format("\n{} light subpaths of pass {} (L)", view3d.particles.subpaths.size(),
                                 view3d.particles.pass)
                   : "\n" + view3d.particles.error;
  drawView3DWindow(raster_->texture().imguiId(), view3DOverlay(view3d, inspector, scene, shown, view), origin, size,
                   r.size, caption, uiScale);
}

void InspectorController::drawRaster(const std::shared_ptr<const Scene>& scene) {
  if (raster_ && view3d.on && view3d.orbit)
    raster_->draw(scene, view3DCameraDesc(view3d), view3dRect.size, view3d.cullBackFaces);
}

std::optional<PixelRect> InspectorController::drawnView3D() const {
  if (!textureInUse_) return std::nullopt;
  return view3dRect;
}

void InspectorController::exportInspection(MessageLine& message) const {
  if (!inspector.on || !inspector.result) {
    message.show("nothing to export: K, then click a pixel of the image");
    return;
  }
  try {
    const std::string path = freshStem("out", "pathlab-paths", {".json"}) + ".json";
    writeTextAtomically(path, inspectionJson(inspector.inspectedSettings, *inspector.result).dump(2) + "\n");
    message.show("wrote " + path);
  } catch (const std::exception& e) {
    message.show(e.what(), true);
  }
}

}  // namespace pathlab::ui
