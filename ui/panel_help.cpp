// The help window (every shortcut, from the shortcut table) and the caption drawn over the image.
#include "ui/viewer.h"

#include "ui/technique_grid.h"

#include <fmt/core.h>
#include <imgui.h>

namespace pathlab::ui {

void Viewer::drawHelpWindow() {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Help (F1)", &showHelp_, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::End();
    return;
  }
  ImGui::TextUnformatted(kMouseHelp);
  ImGui::TextUnformatted(kFlyKeysHelp);
  ImGui::TextUnformatted("Shift with W A S D Q E: three times faster");
  if (ImGui::BeginTable("keys", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit)) {
    for (const Shortcut& s : shortcuts()) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::TextUnformatted(s.keyName);
      ImGui::TableSetColumnIndex(1);
      ImGui::TextUnformatted(s.description);
    }
    ImGui::EndTable();
  }
  ImGui::End();
}

void Viewer::drawImageOverlay() {
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const ImGuiIO& io = ImGui::GetIO();
  const float scale = io.DisplayFramebufferScale.x > 0.f ? io.DisplayFramebufferScale.x : 1.f;
  const ImVec2 origin(static_cast<float>(imageOrigin_.x) / scale, static_cast<float>(imageOrigin_.y) / scale);
  const ImVec2 size(static_cast<float>(imageSize_.x) / scale, static_cast<float>(imageSize_.y) / scale);
  auto caption = [&](const std::string& text, ImVec2 at, ImU32 colour) {
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    draw->AddRectFilled(ImVec2(at.x - 6.f, at.y - 3.f), ImVec2(at.x + extent.x + 6.f, at.y + extent.y + 3.f),
                        IM_COL32(0, 0, 0, 160), 4.f);
    draw->AddText(at, colour, text.c_str());
  };
  if (idleForNoTechnique_) {
    const std::string text = "No technique enabled: switch one on in the grid (or press 1 for all)";
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    caption(text, ImVec2(origin.x + 0.5f * (size.x - extent.x), origin.y + 0.5f * size.y), IM_COL32(255, 200, 80, 255));
  }
  if (!idleForNoTechnique_ && isolatedTechniqueDisabled(edited_)) {
    const std::string text = fmt::format("({},{}) is not enabled: its weighted share is zero", edited_.isolate->s,
                                         edited_.isolate->t);
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    caption(text, ImVec2(origin.x + 0.5f * (size.x - extent.x), origin.y + 0.5f * size.y), IM_COL32(255, 200, 80, 255));
  }
  if (display_.errorView && !shownDisplay().errorView) {
    const std::string text = "error view: " + (referenceStatus_.empty() ? std::string(errors_->reference() ? "waiting for an image of the reference's view" : "no reference (load one, or Ctrl+R)") : referenceStatus_);
    caption(text, ImVec2(origin.x + 10.f, origin.y + 10.f), IM_COL32(255, 200, 80, 255));
  }
  if (shownDisplay().errorView) drawErrorBarOverlay(origin, size);
  // The configuration under the image, readable from the back of a lecture hall.
  std::string text = describe(snapshot_.settings.width > 0 ? snapshot_.settings : edited_);
  text += snapshot_.preview ? fmt::format("  |  preview 1/{}", snapshot_.previewFactor)
                            : fmt::format("  |  {} spp", snapshot_.samplesPerPixel);
  if (userPaused_) text += "  |  paused";
  if (shownDisplay().errorView) text += fmt::format("  |  {} vs reference", pixelErrorName(display_.errorKind));
  const float line = ImGui::GetTextLineHeightWithSpacing();
  caption(text, ImVec2(origin.x + 10.f, origin.y + size.y - line - 6.f), IM_COL32(235, 235, 235, 255));
}

}  // namespace pathlab::ui
