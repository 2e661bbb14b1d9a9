// The help window (every shortcut, from the shortcut table) and the caption drawn over the image.
#include "ui/panels/panels.h"

#include "core/sampling/technique_label.h"
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <imgui.h>

namespace pathlab::ui {

void drawHelpWindow(bool& show) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(io.DisplaySize.x * 0.5f, io.DisplaySize.y * 0.5f), ImGuiCond_Appearing, ImVec2(0.5f, 0.5f));
  if (!ImGui::Begin("Help (F1)", &show, ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings)) {
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

namespace {

// The check's |z| per block of one technique over the image: transparent below 2, then warmer
// up to red at the corrected threshold and beyond, the value written in each block.
void drawZMap(const CheckReport& check, Technique x, ImVec2 origin, ImVec2 size) {
  const TechniqueVerdict* verdict = nullptr;
  for (const TechniqueVerdict& v : check.techniques)
    if (v.technique == x) verdict = &v;
  if (!verdict || check.blocks < 1) return;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const int n = check.blocks;
  for (int b = 0; b < n * n; ++b) {
    // The blocks as TechniqueCheck::blockBounds splits the pixels, in fractions of the image.
    const float x0 = std::ceil(static_cast<float>(b % n) * size.x / static_cast<float>(n));
    const float x1 = std::ceil(static_cast<float>(b % n + 1) * size.x / static_cast<float>(n));
    const float y0 = std::ceil(static_cast<float>(b / n) * size.y / static_cast<float>(n));
    const float y1 = std::ceil(static_cast<float>(b / n + 1) * size.y / static_cast<float>(n));
    const ImVec2 a(origin.x + x0, origin.y + y0), c(origin.x + x1, origin.y + y1);
    const double z = verdict->blockZ[static_cast<size_t>(b)];
    draw->AddRect(a, c, IM_COL32(255, 255, 255, 90));
    const std::string label = z < 0.0 ? std::string("-") : fmt::format("{:.1f}", z);
    if (z >= 0.0) {
      const float heat = static_cast<float>(std::clamp((z - 2.0) / 3.0, 0.0, 1.0));
      draw->AddRectFilled(a, c, IM_COL32(255, static_cast<int>(200 * (1.f - heat)), 40, static_cast<int>(40 + 120 * heat)));
    }
    const ImVec2 extent = ImGui::CalcTextSize(label.c_str());
    draw->AddText(ImVec2(0.5f * (a.x + c.x - extent.x), 0.5f * (a.y + c.y - extent.y)), IM_COL32(255, 255, 255, 230),
                  label.c_str());
  }
  const std::string title = fmt::format("|z| of {} per block: {} (whole image z = {:+.2f})", techniqueLabel(x),
                                        checkStatusName(verdict->status), verdict->wholeImageZ);
  const ImVec2 at(origin.x + 10.f, origin.y + 10.f), extent = ImGui::CalcTextSize(title.c_str());
  draw->AddRectFilled(ImVec2(at.x - 6.f, at.y - 3.f), ImVec2(at.x + extent.x + 6.f, at.y + extent.y + 3.f),
                      IM_COL32(0, 0, 0, 160), 4.f);
  draw->AddText(at, IM_COL32(255, 255, 255, 255), title.c_str());
}

}  // namespace

void drawImageOverlay(const ImageOverlay& o) {
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  auto caption = [&](const std::string& text, ImVec2 at, ImU32 colour) {
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    draw->AddRectFilled(ImVec2(at.x - 6.f, at.y - 3.f), ImVec2(at.x + extent.x + 6.f, at.y + extent.y + 3.f),
                        IM_COL32(0, 0, 0, 160), 4.f);
    draw->AddText(at, colour, text.c_str());
  };
  auto centred = [&](const std::string& text) {
    const ImVec2 extent = ImGui::CalcTextSize(text.c_str());
    caption(text, ImVec2(o.origin.x + 0.5f * (o.size.x - extent.x), o.origin.y + 0.5f * o.size.y),
            IM_COL32(255, 200, 80, 255));
  };
  if (o.idleForNoTechnique) centred("No technique enabled: switch one on in the grid (or press 1 for all)");
  if (!o.idleForNoTechnique && isolatedTechniqueDisabled(o.edited))
    centred(fmt::format("{} is not enabled: its weighted share is zero", techniqueLabel(o.edited.isolate->technique())));
  if (!o.errorViewProblem.empty())
    caption("error view: " + o.errorViewProblem, ImVec2(o.origin.x + 10.f, o.origin.y + 10.f), IM_COL32(255, 200, 80, 255));
  if (o.display.errorView) drawErrorBarOverlay(o.display, o.origin, o.size, o.uiScale);
  if (o.zMap && o.shown->check && !o.shown->preview) drawZMap(*o.shown->check, *o.zMap, o.origin, o.size);
  // The configuration under the image, readable from the back of a lecture hall.
  const RenderSnapshot& shown = *o.shown;
  std::string text = o.side.empty() ? std::string() : o.side + ":  ";
  text += describe(shown.settings.width > 0 ? shown.settings : o.edited);
  text += shown.preview ? fmt::format("  |  preview 1/{}", shown.previewFactor)
                        : fmt::format("  |  {} spp", shown.samplesPerPixel);
  // Side by side, the time says the comparison is fair (both sides run on equal threads).
  if (!o.side.empty()) text += fmt::format("  |  {:.1f} s", shown.renderSeconds);
  if (o.paused) text += "  |  paused";
  if (!o.mapName.empty()) text += "  |  map: " + o.mapName;
  if (o.display.errorView) text += fmt::format("  |  {} vs reference", pixelErrorName(o.display.errorKind));
  // Wrapped to the image's width (a narrow image in lecture mode would cut it), growing upward
  // from the bottom edge.
  const float wrap = std::max(o.size.x - 32.f, 100.f);
  const ImVec2 extent = ImGui::CalcTextSize(text.c_str(), nullptr, false, wrap);
  const ImVec2 at(o.origin.x + 10.f, o.origin.y + o.size.y - extent.y - 9.f);
  draw->AddRectFilled(ImVec2(at.x - 6.f, at.y - 3.f), ImVec2(at.x + extent.x + 6.f, at.y + extent.y + 3.f),
                      IM_COL32(0, 0, 0, 160), 4.f);
  draw->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, IM_COL32(235, 235, 235, 255), text.c_str(), nullptr, wrap);
}

}  // namespace pathlab::ui
