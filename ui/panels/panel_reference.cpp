// The side panel's reference section: load a reference (or take the current image), whether it
// still matches the rendered view, the newest error, and the false-colour error view with its
// colour bar.
#include "ui/panels/panels.h"

#include "core/metrics/log_axis.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

namespace {

const ImVec4 kReferenceWarning(1.f, 0.7f, 0.2f, 1.f);

}  // namespace

void drawReferenceSection(ReferenceState& state, ConvergenceState& convergence, DisplaySettings& display,
                          const RenderSettings& edited, const Image& shown, PanelRequests& requests) {
  ImGui::PushID("reference");
  ErrorTracker& errors = *state.errors;
  const std::shared_ptr<const Image> reference = errors.reference();
  if (reference)
    ImGui::TextWrapped("reference: %s, %d x %d", errors.referenceSource().c_str(), reference->width, reference->height);
  else
    ImGui::TextDisabled("no reference: load an EXR / PFM or take the current image");
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.62f);
  const bool entered = ImGui::InputTextWithHint("##path", "REF.exr or .pfm", &state.typedPath,
                                                ImGuiInputTextFlags_EnterReturnsTrue);
  ImGui::SameLine();
  if ((ImGui::Button("Load") || entered) && !state.typedPath.empty()) requests.loadReference = state.typedPath;
  if (reference) {
    ImGui::SameLine();
    if (ImGui::Button("Drop")) errors.dropReference();
  }
  if (ImGui::Button("Use current image (Ctrl+R)")) requests.actions.push_back(Action::UseImageAsReference);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the image as it is now becomes the reference; render it long first.\n"
                      "Its own run is not plotted: change the configuration to measure another.");
  ImGui::Checkbox("render at the reference's size", &state.matchSize);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the error needs the same pixels: off, the image follows the window");

  if (!state.status.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kReferenceWarning);
    ImGui::TextWrapped("%s", state.status.c_str());
    ImGui::PopStyleColor();
    if (const auto view = errors.referenceView();
        view && (edited.camera != view->camera || !(edited.lens == view->lens)) && ImGui::SmallButton("back to the reference's view"))
      requests.returnToReferenceView = true;
  }
  if (reference && !convergence.series.empty() && !convergence.series.back().points.empty()) {
    const ErrorSeries& sr = convergence.series.back();
    const ErrorPoint& p = sr.points.back();
    ImGui::Text("relMSE %.3g   RMSE %.3g   MAPE %.3g", p.error.relMse, p.error.rmse, p.error.mape);
    ImGui::TextDisabled("run %d at %.1f s, %llu spp (metrics %.1f ms, render thread)", sr.id, p.seconds,
                        static_cast<unsigned long long>(p.spp), errors.lastMetricMilliseconds());
  }
  ImGui::Checkbox("convergence plot and technique table (P)", &convergence.show);

  ImGui::BeginDisabled(!reference);
  ImGui::Checkbox("error view (X)", &display.errorView);
  ImGui::EndDisabled();
  if (display.errorView && reference) {
    ImGui::SameLine();
    int kind = static_cast<int>(display.errorKind);
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x);
    if (ImGui::Combo("##kind", &kind, "relative squared\0absolute\0")) {
      display.errorKind = static_cast<PixelError>(kind);
      // Relative squared errors span many decades more than absolute ones.
      if (display.errorKind == PixelError::Absolute) display.errorLogMin = -3.f, display.errorLogMax = 0.f;
      else display.errorLogMin = -4.f, display.errorLogMax = 0.f;
    }
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("relative squared: (x - r)^2 / (r^2 + 0.01), its mean is relMSE\nabsolute: |x - r|");
    ImGui::Checkbox("log scale", &display.errorLog);
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
    if (display.errorLog) {
      ImGui::DragFloatRange2("##range", &display.errorLogMin, &display.errorLogMax, 0.05f, -12.f, 6.f, "1e%.1f", "1e%.1f");
      display.errorLogMax = std::max(display.errorLogMax, display.errorLogMin + 0.1f);
    } else {
      ImGui::DragFloat("##max", &display.errorLinearMax, 0.005f, 1e-6f, 1e6f, "max %.3g", ImGuiSliderFlags_Logarithmic);
      display.errorLinearMax = std::max(display.errorLinearMax, 1e-6f);
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("auto") && shown.width == reference->width && shown.height == reference->height) {
      // The 2% and 99.5% quantiles: a few fireflies do not stretch the scale.
      const auto [lo, hi] = positiveQuantiles(pixelErrors(shown, *reference, display.errorKind), 0.02, 0.995);
      if (hi > 0.f) {
        display.errorLogMin = std::floor(std::log10(lo) * 2.f) / 2.f;
        display.errorLogMax = std::max(std::ceil(std::log10(hi) * 2.f) / 2.f, display.errorLogMin + 0.5f);
        display.errorLinearMax = hi;
      }
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("fit the scale to the image's 2%% .. 99.5%% quantiles");
    drawErrorBar(display);
  }
  ImGui::PopID();
}

void drawViridisBar(ImDrawList* draw, ImVec2 origin, float w, float h) {
  constexpr int kSegments = 32;
  for (int i = 0; i < kSegments; ++i) {
    const Vec3 a = viridis(static_cast<float>(i) / kSegments), b = viridis(static_cast<float>(i + 1) / kSegments);
    const ImU32 ca = ImGui::ColorConvertFloat4ToU32(ImVec4(a.r, a.g, a.b, 1.f));
    const ImU32 cb = ImGui::ColorConvertFloat4ToU32(ImVec4(b.r, b.g, b.b, 1.f));
    draw->AddRectFilledMultiColor(ImVec2(origin.x + w * static_cast<float>(i) / kSegments, origin.y),
                                  ImVec2(origin.x + w * static_cast<float>(i + 1) / kSegments, origin.y + h), ca, cb,
                                  cb, ca);
  }
}

namespace {

// The per-pixel error at position t in [0, 1] of the colour scale.
double errorScaleValue(const DisplaySettings& d, float t) {
  return d.errorLog ? std::pow(10.0, d.errorLogMin + t * (d.errorLogMax - d.errorLogMin))
                    : static_cast<double>(t * d.errorLinearMax);
}

}  // namespace

void drawErrorBar(const DisplaySettings& d) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  const float w = ImGui::GetContentRegionAvail().x, h = ImGui::GetTextLineHeight();
  drawViridisBar(draw, p, w, h);
  ImGui::Dummy(ImVec2(w, h));
  // Labels at both ends and the middle, in the error's own units.
  const auto value = [&](float t) { return errorScaleValue(d, t); };
  const std::string lo = d.errorLog ? tickLabel(value(0.f)) : "0", mid = tickLabel(value(0.5f)), hi = tickLabel(value(1.f));
  const float x0 = ImGui::GetCursorPosX();
  ImGui::TextUnformatted(lo.c_str());
  ImGui::SameLine(x0 + 0.5f * (w - ImGui::CalcTextSize(mid.c_str()).x));
  ImGui::TextUnformatted(mid.c_str());
  ImGui::SameLine(x0 + w - ImGui::CalcTextSize(hi.c_str()).x);
  ImGui::TextUnformatted(hi.c_str());
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s per pixel, %s scale%s", pixelErrorName(d.errorKind), d.errorLog ? "log" : "linear",
                     d.errorLog ? "; darkest: at or below the low end" : "");
  ImGui::PopStyleColor();
}

void drawErrorBarOverlay(const DisplaySettings& d, ImVec2 imageOrigin, ImVec2 imageSize, float uiScale) {
  // The scale beside the picture it explains, top right of the image area.
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  const float line = ImGui::GetTextLineHeight(), pad = 6.f * uiScale;
  const std::string title = d.errorKind == PixelError::RelativeSquared ? "(x - r)^2 / (r^2 + 0.01)" : "|x - r|";
  const float w = std::max(std::min(260.f * uiScale, 0.45f * imageSize.x), ImGui::CalcTextSize(title.c_str()).x);
  const float h = 0.8f * line;
  const ImVec2 p0(std::max(imageOrigin.x, imageOrigin.x + imageSize.x - w - 2.f * pad - 8.f * uiScale),
                  imageOrigin.y + 8.f * uiScale);
  const ImVec2 p1(p0.x + w + 2.f * pad, p0.y + 2.f * line + h + 3.f * pad);
  draw->AddRectFilled(p0, p1, IM_COL32(0, 0, 0, 170), 4.f);
  draw->AddText(ImVec2(p0.x + pad, p0.y + pad), IM_COL32(235, 235, 235, 255), title.c_str());
  const ImVec2 b0(p0.x + pad, p0.y + line + 2.f * pad);
  drawViridisBar(draw, b0, w, h);
  const auto value = [&](float t) { return errorScaleValue(d, t); };
  const float ly = b0.y + h + pad;
  const ImU32 text = IM_COL32(220, 220, 220, 255);
  for (const float t : {0.f, 0.25f, 0.5f, 0.75f, 1.f}) {
    if (!d.errorLog && t == 0.f) {
      draw->AddText(ImVec2(b0.x, ly), text, "0");
      continue;
    }
    const std::string label = tickLabel(value(t));
    const float lw = ImGui::CalcTextSize(label.c_str()).x;
    if ((t == 0.25f || t == 0.75f) && w < 200.f * uiScale) continue;  // room for three labels only
    const float x = std::clamp(b0.x + t * w - 0.5f * lw, b0.x, b0.x + w - lw);
    draw->AddLine(ImVec2(b0.x + t * w, b0.y + h), ImVec2(b0.x + t * w, b0.y + h + 3.f * uiScale), text);
    draw->AddText(ImVec2(x, ly), text, label.c_str());
  }
}

}  // namespace pathlab::ui
