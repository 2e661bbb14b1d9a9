// The live technique pyramid (Veach 1997, fig. 10.3 as it converges): a thumbnail of every (s,t) up
// to the chosen length, laid out like the technique grid, each with its own exposure; with merges
// enabled, each length k >= 2 has a second row, its merges M(s, k + 2 - s) under column s. A click
// isolates the technique in the main image.
#include "ui/panels/panels.h"

#include "core/sampling/technique_label.h"

#include <algorithm>
#include <imgui.h>
#include <optional>

namespace pathlab::ui {

const Texture* PyramidImages::texture(Technique x, bool unweighted) const {
  for (size_t i = 0; i < thumbnails.size(); ++i)
    if (thumbnails[i].technique() == x && 2 * i + 1 < textures.size()) {
      const Texture& t = textures[2 * i + (unweighted ? 1 : 0)];
      return t.empty() ? nullptr : &t;
    }
  return nullptr;
}

bool PyramidImages::hasEquiangular() const {
  return std::any_of(thumbnails.begin(), thumbnails.end(),
                     [](const TechniqueThumbnail& x) { return x.kind == TechniqueKind::Equiangular; });
}

bool PyramidImages::hasMerges() const {
  return std::any_of(thumbnails.begin(), thumbnails.end(), [](const TechniqueThumbnail& x) { return x.kind == TechniqueKind::Merge; });
}

// The pyramid's largest share of the width beside the side panel: 45 %, so that at 1280 x 720 in
// lecture mode the thumbnails of a 1.5:1 scene stay large enough for their (s,t) labels.
constexpr float kMaxShare = 0.45f;

float pyramidPanelWidth(PyramidView& view, int maxLength, float availableWidth, float height, float uiScale,
                        std::optional<float> imageAspect, bool merges, bool equiangular) {
  const ImGuiStyle& style = ImGui::GetStyle();
  const int lengths = std::max(1, std::min(view.length, maxLength));
  const int rows = merges ? 2 * lengths - 1 : lengths;  // a row of merges under each length >= 2
  const float n = static_cast<float>(lengths + (equiangular ? 2 : 1));  // thumbnails in the longest row
  // Rows of thumbnails fill the height below the header, at most 100 pixels (x UI scale) tall.
  const float frame = 2.f * 2.f;  // image button padding
  // Both pyramids, weighted above unweighted, when each row can still be 48 pixels tall; else one
  // of them with a switch.
  const float line = ImGui::GetFrameHeightWithSpacing();
  const float rowSpace = frame + style.ItemSpacing.y;
  view.both = (height - 6.f * line - 2.f * style.WindowPadding.y) / static_cast<float>(2 * rows) - rowSpace >=
              48.f * uiScale;
  const float header = (view.both ? 6.f : 4.f) * line + 2.f * style.WindowPadding.y;
  const int stacked = view.both ? 2 * rows : rows;
  float h = std::clamp((height - header) / static_cast<float>(stacked) - rowSpace, 16.f, 100.f * uiScale);
  // The thumbnails have the image's aspect, and the image gets what the panel leaves:
  // width = n (h a + c) + p with a = (W - width) / H, solved for width (no feedback through the
  // rendered image, which would restart the render until it settled).
  const float c = frame + style.ItemSpacing.x, p = 2.f * style.WindowPadding.x;
  if (imageAspect) {
    // The image has the camera's aspect whatever room it gets (ui/display/image_rect.h): so do the
    // thumbnails, and the panel is n (h a + c) + p wide.
    const float a = *imageAspect;
    if (n * (h * a + c) + p > kMaxShare * availableWidth) h = std::max(((kMaxShare * availableWidth - p) / n - c) / a, 16.f);
    const float width = std::max(n * (h * a + c) + p, std::min(220.f * uiScale, 0.5f * availableWidth));
    view.thumbnail = {h * a, h};
    return width;
  }
  auto widthFor = [&](float thumbHeight) {
    return (n * thumbHeight * availableWidth / height + n * c + p) / (1.f + n * thumbHeight / height);
  };
  float width = widthFor(h);
  if (width > kMaxShare * availableWidth) {
    // Too wide: shrink the thumbnails until the panel takes its largest share of the space.
    const float w = kMaxShare * availableWidth, a = (availableWidth - w) / height;
    h = std::max(((w - p) / n - c) / a, 16.f);
    width = widthFor(h);
  }
  // Never narrower than its header text needs (small windows), nor wider than half the space.
  width = std::max(width, std::min(220.f * uiScale, 0.5f * availableWidth));
  view.thumbnail = {h * (availableWidth - width) / height, h};
  return width;
}

namespace {

// One thumbnail: its texture (or a button until it arrives) with its label on it, framed when the
// main image shows it; a click isolates it.
void drawThumbnail(Technique x, const PyramidImages& images, EstimatorState& estimator, bool unweighted, ImVec2 size,
                   float uiScale) {
  const EstimatorMode shownMode = unweighted ? EstimatorMode::IsolateUnweighted : EstimatorMode::IsolateWeighted;
  ImGui::PushID(static_cast<int>(x.index()));
  const Texture* texture = images.texture(x, unweighted);
  const bool isolated = estimator.mode == shownMode && estimator.isolated == x;
  const std::string label = techniqueLabel(x);
  bool clicked = false;
  if (texture) {
    clicked = ImGui::ImageButton(texture->imguiId(), size, ImVec2(0, 0), ImVec2(1, 1), 2,
                                 isolated ? ImVec4(0.9f, 0.6f, 0.15f, 1.f) : ImVec4(0, 0, 0, 0));
  } else {
    clicked = ImGui::Button(label.c_str(), ImVec2(size.x + 4.f, size.y + 4.f));
  }
  const ImVec2 extent = ImGui::CalcTextSize(label.c_str());
  // Its (s,t) on the thumbnail itself, readable on a projector without hovering; not on
  // thumbnails too small to hold it (the tooltip still names it).
  if (texture && extent.x + 8.f * uiScale <= size.x && extent.y + 6.f * uiScale <= size.y) {
    const ImVec2 at(ImGui::GetItemRectMin().x + 4.f * uiScale, ImGui::GetItemRectMin().y + 3.f * uiScale);
    ImDrawList* draw = ImGui::GetWindowDrawList();
    draw->AddRectFilled(ImVec2(at.x - 2.f, at.y - 1.f), ImVec2(at.x + extent.x + 2.f, at.y + extent.y + 1.f),
                        IM_COL32(0, 0, 0, 150), 3.f);
    draw->AddText(at, x.isMerge() ? IM_COL32(150, 220, 255, 240) : IM_COL32(255, 255, 255, 235), label.c_str());
  }
  if (isolated)  // the technique the main image shows, framed so the back row sees it too
    ImGui::GetWindowDrawList()->AddRect(ImGui::GetItemRectMin(), ImGui::GetItemRectMax(), IM_COL32(240, 160, 40, 255),
                                        0.f, 0, 3.f * uiScale);
  if (ImGui::IsItemHovered()) {
    const char* shown = unweighted ? "unweighted" : "weighted";
    if (x.isMerge())
      ImGui::SetTooltip("M(%d,%d), length %d, %s: light subpath vertex %d merged with camera subpath vertex %d\n"
                        "within the pass's radius; click to isolate it",
                        x.s, x.t, x.length(), shown, x.s - 1, x.t - 1);
    else if (x.isEquiangular())
      ImGui::SetTooltip("E(1,%d), length %d, %s: C(1,%d)'s path with its camera vertex next to the light placed in\n"
                        "the medium toward the light point (equiangular sampling); click to isolate it",
                        x.t, x.length(), shown, x.t);
    else
      ImGui::SetTooltip("(s,t) = (%d,%d), length %d, %s: click to isolate it", x.s, x.t, x.length(), shown);
  }
  if (clicked) isolate(estimator, x, unweighted);
  ImGui::PopID();
}

// One pyramid, weighted or unweighted, laid out like the technique grid: length k's connections
// (s = 0..k) in a row, then, when merges are shown, its merges M(s, k + 2 - s) under columns 2..k.
void drawPyramid(const PyramidView& view, const PyramidImages& images, EstimatorState& estimator, bool unweighted,
                 float uiScale) {
  ImGui::PushID(unweighted ? "unweighted" : "weighted");
  const int rows = std::min(view.length, estimator.settings.maxLength);
  const ImVec2 size(view.thumbnail.x, view.thumbnail.y);
  const bool merges = images.hasMerges();
  for (int k = 1; k <= rows; ++k) {
    for (const Technique x : techniquesOfLength(k)) {
      if (x.s > 0) ImGui::SameLine();
      drawThumbnail(x, images, estimator, unweighted, size, uiScale);
    }
    // E(1, k) at the end of its length's row, where bpt samples it.
    if (k >= 2 && images.texture(Technique::equiangular(k), unweighted)) {
      ImGui::SameLine();
      drawThumbnail(Technique::equiangular(k), images, estimator, unweighted, size, uiScale);
    }
    if (!merges || k < 2) continue;
    // Columns s = 0 and 1 hold no merge: keep them empty so M(s, .) sits under (s, .).
    ImGui::Dummy(ImVec2(size.x + 4.f, size.y + 4.f));
    ImGui::SameLine();
    ImGui::Dummy(ImVec2(size.x + 4.f, size.y + 4.f));
    for (const Technique x : techniquesOfLength(k, TechniqueFamilies::Merges)) {
      ImGui::SameLine();
      drawThumbnail(x, images, estimator, unweighted, size, uiScale);
    }
  }
  ImGui::PopID();
}

}  // namespace

void drawPyramidWindow(PyramidView& view, const PyramidImages& images, EstimatorState& estimator, PanelRect rect,
                       float uiScale) {
  ImGui::SetNextWindowPos(ImVec2(rect.x, rect.y));
  ImGui::SetNextWindowSize(ImVec2(rect.width, rect.height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
  if (!ImGui::Begin("Technique pyramid (G)", &view.show, flags)) {
    ImGui::End();
    return;
  }
  const char* sharesSum = "the shares sum to the image";
  if (!view.both) {
    ImGui::Checkbox("unweighted", &view.unweighted);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("weighted: each technique's MIS share (%s)\n"
                        "unweighted: each technique's own estimate of its whole length", sharesSum);
  }
  ImGui::Checkbox("own exposure each", &view.ownExposure);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("on: every thumbnail auto-exposed (all visible)\n"
                      "off: all at the image's exposure (the weighted shares compare directly)");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s", images.thumbnails.empty() ? "waiting for the first full pass ..."
                                                : images.hasMerges() ? "rows: length k, then its merges M; columns: s; click to isolate"
                                                : images.hasEquiangular()
                                                    ? "rows: length k; columns: s, then the equiangular E(1,k); click to isolate"
                                                    : "rows: length k; columns: s; click to isolate");
  ImGui::PopStyleColor();
  if (view.both) {
    ImGui::TextWrapped("weighted: MIS shares, %s", sharesSum);
    drawPyramid(view, images, estimator, false, uiScale);
    ImGui::TextWrapped("unweighted: each technique alone");
    drawPyramid(view, images, estimator, true, uiScale);
  } else {
    drawPyramid(view, images, estimator, view.unweighted, uiScale);
  }
  if (estimator.mode != EstimatorMode::Combine && ImGui::Button("show all combined (MIS)"))
    estimator.mode = EstimatorMode::Combine;
  ImGui::End();
}

}  // namespace pathlab::ui
