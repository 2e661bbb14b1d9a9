// The technique maps section of the side panel: the chooser and the legend or colour bar.
#include "core/maps/map_colours.h"
#include "core/render/render_settings.h"
#include "core/sampling/technique_label.h"
#include "ui/panels/panels.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

ImU32 colour(const Vec3& c) { return ImGui::ColorConvertFloat4ToU32(ImVec4(c.r, c.g, c.b, 1.f)); }

// A square of the map's colour (hatched: the cannot-sample key; striped: a merge, as the
// dominant map draws it) and its label, on one line.
void swatch(const Vec3& c, const std::string& label, bool hatched = false, bool striped = false) {
  const float side = ImGui::GetTextLineHeight();
  const ImVec2 p = ImGui::GetCursorScreenPos();
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddRectFilled(p, ImVec2(p.x + side, p.y + side), colour(c));
  if (striped)
    for (float y = side / 6.f; y < side; y += side / 3.f)
      draw->AddLine(ImVec2(p.x, p.y + y), ImVec2(p.x + side, p.y + y), colour(c * (1.f - kMergeStripeDarkening)), 1.5f);
  if (hatched)
    for (float d = 0.f; d < 2.f * side; d += side / 3.f)
      draw->AddLine(ImVec2(p.x + std::max(0.f, d - side), p.y + std::min(d, side)),
                    ImVec2(p.x + std::min(d, side), p.y + std::max(0.f, d - side)), colour(kHatchColour), 1.5f);
  draw->AddRect(p, ImVec2(p.x + side, p.y + side), IM_COL32(128, 128, 128, 255));
  ImGui::Dummy(ImVec2(side, side));
  ImGui::SameLine();
  ImGui::TextUnformatted(label.c_str());
}

void techniqueChooser(MapView& view, TechniqueFamilies families) {
  int st[2] = {view.technique.s, view.technique.t};
  bool merge = view.technique.isMerge(), equiangular = view.technique.isEquiangular();
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 6.f);
  bool changed = ImGui::InputInt2("(s,t)##mapTechnique", st);
  if (covers(families, TechniqueKind::Merge)) {
    ImGui::SameLine();
    changed |= ImGui::Checkbox("merge M(s,t)", &merge);
  }
  // bpt's equiangular techniques in fog: E(1,t), s = 1.
  if (covers(families, TechniqueKind::Equiangular)) {
    ImGui::SameLine();
    changed |= ImGui::Checkbox("equiangular E(1,t)", &equiangular);
  }
  if (changed) {
    const Technique x{std::max(st[0], 0), std::max(st[1], 1),
                      merge ? TechniqueKind::Merge : equiangular ? TechniqueKind::Equiangular : TechniqueKind::Connection};
    if (x.valid() && x.length() <= view.length) view.technique = x;
  }
}

void shareBar(const char* what) {
  const float w = ImGui::GetContentRegionAvail().x * 0.8f, h = ImGui::GetTextLineHeight();
  drawViridisBar(ImGui::GetWindowDrawList(), ImGui::GetCursorScreenPos(), w, h);
  ImGui::Dummy(ImVec2(w, h));
  ImGui::Text("0%*s1  %s", static_cast<int>(w / ImGui::CalcTextSize(" ").x) - 4, "", what);
}

}  // namespace

void drawTechniqueMapSection(MapView& view, int maxLength, TechniqueFamilies families, bool waiting) {
  ImGui::PushID("maps");
  ImGui::Checkbox("show a technique map over the image", &view.show);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("from the technique pyramid's weighted films; the first time restarts the image once");
  const int longest = std::min(maxLength, kMaxPyramidLength);
  view.length = std::clamp(view.length, 1, longest);
  ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.f);
  ImGui::SliderInt("techniques up to length", &view.length, 1, longest);
  if (!view.show) {
    ImGui::PopID();
    return;
  }
  int kind = static_cast<int>(view.kind);
  ImGui::RadioButton("dominant", &kind, 0);
  ImGui::SameLine();
  ImGui::RadioButton("share", &kind, 1);
  ImGui::SameLine();
  ImGui::RadioButton("cannot sample", &kind, 2);
  ImGui::RadioButton("variance", &kind, 3);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the variance of one pass's estimate by the technique alone: where its noise is");
  ImGui::SameLine();
  ImGui::RadioButton("most variance", &kind, 4);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the technique whose estimate has the most variance: where the noise comes from");
  view.kind = static_cast<MapKind>(kind);
  if (view.technique.length() > view.length) view.technique = Technique{1, view.length};
  if (waiting) ImGui::TextDisabled("waiting for the first full pass ...");
  switch (view.kind) {
    case MapKind::Dominant:
    case MapKind::VarianceDominant: {
      const bool variance = view.kind == MapKind::VarianceDominant;
      view.dominantLength = std::clamp(view.dominantLength, 0, view.length);
      if (!variance) {
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.f);
        ImGui::SliderInt("length (0: all)", &view.dominantLength, 0, view.length);
      }
      const int first = view.dominantLength > 0 && !variance ? view.dominantLength : 1;
      const int last = view.dominantLength > 0 && !variance ? view.dominantLength : view.length;
      int column = 0;
      for (const Technique x : TechniqueRange(first, last, families)) {
        if (column++ % 4 != 0) ImGui::SameLine(static_cast<float>((column - 1) % 4) * ImGui::GetFontSize() * 4.5f);
        swatch(techniqueColour(x), techniqueLabel(x), false, x.isMerge());
      }
      swatch(kTieColour, "tie (within 1 %)");
      ImGui::SameLine();
      swatch(kEmptyColour, "no light");
      break;
    }
    case MapKind::Share:
      techniqueChooser(view, families);
      shareBar("of the image");
      break;
    case MapKind::Variance: {
      techniqueChooser(view, families);
      const float w = ImGui::GetContentRegionAvail().x * 0.8f, h = ImGui::GetTextLineHeight();
      drawViridisBar(ImGui::GetWindowDrawList(), ImGui::GetCursorScreenPos(), w, h);
      ImGui::Dummy(ImVec2(w, h));
      ImGui::Text("1e-%d%*stop", static_cast<int>(kVarianceDecades),
                  static_cast<int>(w / ImGui::CalcTextSize(" ").x) - 8, "");
      ImGui::TextDisabled("log scale; top: 99.9th percentile of all");
      swatch(kEmptyColour, "no variance");
      break;
    }
    case MapKind::CannotSample:
      techniqueChooser(view, families);
      shareBar("of its length");
      swatch(viridis(0.f), "cannot sample (hatched)", true);
      swatch(viridis(0.f), "weighted away");
      swatch(kEmptyColour, "no light of this length");
      break;
  }
  ImGui::PopID();
}

}  // namespace pathlab::ui
