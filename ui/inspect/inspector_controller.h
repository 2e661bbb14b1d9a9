// The path inspector and the 3D view in the viewer: the picked sample replayed when it or the shown
// image changes, its overlay and window, the 3D view's raster, particles and caption, and the
// inspection's export (Ctrl+J). The panels and the input edit `inspector` and `view3d` directly.
#pragma once

#include "ui/display/image_rect.h"
#include "ui/gl/scene_raster.h"
#include "ui/inspect/path_inspector.h"
#include "ui/inspect/view3d.h"
#include "ui/message_line.h"
#include "ui/panels/panels.h"

#include <memory>
#include <optional>

namespace pathlab::ui {

class InspectorController {
 public:
  PathInspectorState inspector;
  View3DState view3d;
  // Where the 3D view goes this frame, framebuffer pixels (empty: not shown).
  PixelRect view3dRect;

  // The inspector's window along the bottom of `room` (framebuffer pixels), which it leaves
  // shorter: its table and bars never cover the image. Nothing while it is off or the UI hidden.
  PixelRect placeWindow(PixelRect room, bool showUi, float uiScale, float framebufferScale);
  void drawWindow(PanelRequests& requests);
  // Replays the picked sample when it or the shown image's settings changed; the 3D view's camera
  // and particles follow the scene and the newest full pass of `snapshot`.
  void update(const std::shared_ptr<const Scene>& scene, const RenderSettings& shown, const RenderSnapshot& snapshot,
              const CameraDesc& camera);
  // The inspected path over the image (ImGui coordinates) and the 3D view's window.
  void drawOverlays(const Scene& scene, const RenderSettings& shown, ImVec2 imageOrigin, ImVec2 imageSize,
                    float framebufferScale, float uiScale);
  // Rasterises the scene for the 3D view (outside the ImGui frame, before its draw data).
  void drawRaster(const std::shared_ptr<const Scene>& scene);
  // Where the 3D view was drawn in the last frame (nothing when it is off).
  std::optional<PixelRect> drawnView3D() const;
  // Writes the inspected sample as JSON in out/; the message line says where (or why not).
  void exportInspection(MessageLine& message) const;

 private:
  InspectorOverlay overlay_;  // of inspector's result, recomputed when it replays or the selection changes
  int overlaySelected_ = -1;   // the selected technique overlay_ was drawn for
  std::unique_ptr<SceneRaster> raster_;  // while the 3D view is shown
  bool textureInUse_ = false;            // this frame's draw lists show the raster's texture
  PanelRect window_;                     // the inspector's window, ImGui coordinates (empty: none)
};

}  // namespace pathlab::ui
