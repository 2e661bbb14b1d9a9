// The 3D view's drawing (ui/inspect/view3d.h): the scene's triangles as ui/gl/scene_raster.h drew them, the
// frustum, lights, particles and inspected paths over them, and a caption.
#include "ui/panels/panels.h"

namespace pathlab::ui {

void drawView3DWindow(void* texture, const InspectorOverlay& overlay, ImVec2 origin, ImVec2 size, Vec2i raster,
                      const std::string& caption, float uiScale) {
  if (raster.x <= 0 || raster.y <= 0) return;
  const ImVec2 end(origin.x + size.x, origin.y + size.y);
  // The triangles under the panels, like the image; OpenGL's rows run bottom up.
  ImGui::GetBackgroundDrawList()->AddImage(texture, origin, end, ImVec2(0.f, 1.f), ImVec2(1.f, 0.f));
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  draw->PushClipRect(origin, end, true);
  drawOverlayShapes(draw, overlay, origin, size, raster, uiScale);
  const float pad = 6.f * uiScale;
  draw->AddText(ImVec2(origin.x + pad, origin.y + pad), IM_COL32(220, 220, 225, 200), caption.c_str());
  draw->PopClipRect();
}

}  // namespace pathlab::ui
