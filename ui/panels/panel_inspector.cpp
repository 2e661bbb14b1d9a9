// The path inspector: its section of the side panel (on / off, the 3D view and its particles), its
// window below the image (the picked sample's techniques and, for the selected one, its path under
// every technique of its length) and its overlay over the image and the 3D view.
#include "ui/panels/panels.h"

#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

namespace {

ImU32 roleColour(SegmentRole role) {
  switch (role) {
    case SegmentRole::CameraSubpath: return IM_COL32(90, 200, 255, 255);
    case SegmentRole::LightSubpath: return IM_COL32(255, 165, 60, 255);
    case SegmentRole::Connection: return IM_COL32(120, 240, 120, 220);
    case SegmentRole::BlockedConnection: return IM_COL32(255, 80, 80, 220);
    case SegmentRole::Selected: return IM_COL32(255, 240, 70, 255);
    case SegmentRole::Frustum: return IM_COL32(200, 200, 210, 150);
    case SegmentRole::Particle: return IM_COL32(255, 220, 120, 255);
    case SegmentRole::MergeDisk: return IM_COL32(255, 80, 230, 255);
    case SegmentRole::ChainCurrent:
    case SegmentRole::ChainAccepted:
    case SegmentRole::ChainRejected: return IM_COL32_WHITE;  // a hue a chain (drawOverlayShapes)
  }
  return IM_COL32_WHITE;
}

void dashed(ImDrawList* draw, ImVec2 a, ImVec2 b, ImU32 colour, float dash, float thickness) {
  const float length = std::hypot(b.x - a.x, b.y - a.y);
  const int n = std::max(1, static_cast<int>(length / dash));
  for (int i = 0; i < n; i += 2) {
    const float t0 = static_cast<float>(i) / static_cast<float>(n), t1 = static_cast<float>(i + 1) / static_cast<float>(n);
    draw->AddLine(ImVec2(a.x + (b.x - a.x) * t0, a.y + (b.y - a.y) * t0), ImVec2(a.x + (b.x - a.x) * t1, a.y + (b.y - a.y) * t1),
                  colour, thickness);
  }
}

}  // namespace

void drawOverlayShapes(ImDrawList* draw, const InspectorOverlay& overlay, ImVec2 origin, ImVec2 size, Vec2i raster,
                       float uiScale) {
  const float sx = size.x / static_cast<float>(raster.x), sy = size.y / static_cast<float>(raster.y);
  auto screen = [&](Vec2 p) { return ImVec2(origin.x + p.x * sx, origin.y + p.y * sy); };
  const float s = uiScale;
  for (const InspectorSegment& seg : overlay.segments) {
    ImU32 c = roleColour(seg.role);
    float width = seg.role == SegmentRole::Selected || seg.role == SegmentRole::MergeDisk ? 3.f
                  : seg.role == SegmentRole::Particle || seg.role == SegmentRole::Frustum ? 1.f
                                                                                          : 1.8f;
    if (seg.role == SegmentRole::ChainCurrent || seg.role == SegmentRole::ChainAccepted ||
        seg.role == SegmentRole::ChainRejected) {
      // A hue a chain: its current path thick and opaque, its accepted moves solid, its rejected
      // proposals faint.
      float r = 1.f, g = 1.f, b = 1.f;
      ImGui::ColorConvertHSVtoRGB(seg.shade, seg.role == SegmentRole::ChainRejected ? 0.45f : 0.75f, 1.f, r, g, b);
      const float alpha = seg.role == SegmentRole::ChainCurrent ? 1.f : seg.role == SegmentRole::ChainAccepted ? 0.8f : 0.28f;
      c = ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, alpha));
      width = seg.role == SegmentRole::ChainCurrent ? 3.f : seg.role == SegmentRole::ChainAccepted ? 1.5f : 1.f;
    }
    if (seg.role == SegmentRole::Particle) {
      // Dim red where little throughput is left, bright yellow where much is: a warm glow.
      const float k = seg.shade;
      c = IM_COL32(static_cast<int>(120.f + 135.f * k), static_cast<int>(40.f + 190.f * k), static_cast<int>(30.f + 90.f * k),
                   static_cast<int>(90.f + 110.f * k));
    }
    if (seg.role == SegmentRole::BlockedConnection) dashed(draw, screen(seg.a), screen(seg.b), c, 6.f * s, 1.5f * s);
    else draw->AddLine(screen(seg.a), screen(seg.b), c, width * s);
  }
  for (const InspectorMarker& m : overlay.markers) {
    const ImVec2 p = screen(m.p);
    const ImU32 c = roleColour(m.cameraSide ? SegmentRole::CameraSubpath : SegmentRole::LightSubpath);
    const float r = 4.f * s;
    if (m.type == VertexType::Light) draw->AddTriangleFilled(ImVec2(p.x, p.y - r), ImVec2(p.x - r, p.y + r), ImVec2(p.x + r, p.y + r), c);
    else if (m.type == VertexType::Camera) draw->AddRectFilled(ImVec2(p.x - r, p.y - r), ImVec2(p.x + r, p.y + r), c);
    else if (m.type == VertexType::Medium) draw->AddQuadFilled(ImVec2(p.x, p.y - r), ImVec2(p.x + r, p.y), ImVec2(p.x, p.y + r), ImVec2(p.x - r, p.y), c);  // in a medium: a diamond
    else if (m.delta) draw->AddCircle(p, r, c, 0, 2.f * s);  // a delta lobe: hollow (no connection can reach it)
    else draw->AddCircleFilled(p, r, c);
  }
}

void drawInspectorOverlay(const InspectorOverlay& overlay, const PathInspectorState& state, ImVec2 origin, ImVec2 size,
                          Vec2i raster, float uiScale) {
  if (!state.on || !state.pixel || raster.x <= 0 || raster.y <= 0) return;
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  draw->PushClipRect(origin, ImVec2(origin.x + size.x, origin.y + size.y), true);
  drawOverlayShapes(draw, overlay, origin, size, raster, uiScale);
  const float sx = size.x / static_cast<float>(raster.x), sy = size.y / static_cast<float>(raster.y);
  auto screen = [&](Vec2 p) { return ImVec2(origin.x + p.x * sx, origin.y + p.y * sy); };
  const float s = uiScale;
  // The picked pixel.
  const Vec2i px = *state.pixel;
  const ImVec2 p0 = screen(Vec2(px)), p1 = screen(Vec2(px) + Vec2(1.f));
  const float pad = 5.f * s;
  draw->AddRect(ImVec2(p0.x - pad, p0.y - pad), ImVec2(p1.x + pad, p1.y + pad), IM_COL32(255, 255, 255, 255), 0.f, 0, 2.f * s);
  draw->PopClipRect();
}

void drawInspectorSection(PathInspectorState& state, View3DState& view3d, PanelRequests& requests) {
  ImGui::PushID("inspector");
  bool on = state.on;
  if (ImGui::Checkbox("Inspect paths (K): click a pixel", &on)) requests.actions.push_back(Action::ToggleInspector);
  if (state.on) ImGui::TextDisabled("its techniques: in the window below the image");
  bool show3d = view3d.on;
  if (ImGui::Checkbox("3D view beside the image (O)", &show3d)) requests.actions.push_back(Action::ToggleView3D);
  if (view3d.on) {
    ImGui::Indent();
    ImGui::Checkbox("see into rooms: hide faces turned away", &view3d.cullBackFaces);
    bool particles = view3d.particles.on;
    if (ImGui::Checkbox(view3d.chains.shown ? "the Metropolis chains' paths (L)" : "light particles (L)", &particles))
      requests.actions.push_back(Action::ToggleParticles);
    if (view3d.particles.on && view3d.chains.shown) {
      const int watched = view3d.chains.summary ? static_cast<int>(view3d.chains.summary->watched.size()) : 0;
      if (watched > 1) {
        ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.f);
        ImGui::SliderInt("chains", &view3d.chains.count, 1, watched, "%d", ImGuiSliderFlags_AlwaysClamp);
      }
      ImGui::Checkbox("rejected proposals (faint)", &view3d.chains.rejected);
    } else if (view3d.particles.on) {
      ImGui::SetNextItemWidth(ImGui::GetFontSize() * 8.f);
      ImGui::SliderInt("light subpaths", &view3d.particles.count, 1, LightParticles::kMaxCount, "%d",
                       ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    }
    if (ImGui::SmallButton("export 3D view as PNG (Ctrl+E)")) requests.actions.push_back(Action::ExportView3D);
    ImGui::Unindent();
  }
  ImGui::PopID();
}

namespace {

// The techniques the sample tried, a row each; a click selects one (its full path is highlighted).
void drawTechniqueRows(PathInspectorState& state) {
  const SampleInspection& in = *state.result;
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV | ImGuiTableFlags_SizingStretchProp |
                                ImGuiTableFlags_ScrollY;
  if (!ImGui::BeginTable("techniques", 5, flags)) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("(s,t)");
  ImGui::TableSetupColumn("unweighted");
  ImGui::TableSetupColumn("weight");
  ImGui::TableSetupColumn("weighted");
  ImGui::TableSetupColumn("lands");
  ImGui::TableHeadersRow();
  for (size_t i = 0; i < in.trace.records.size(); ++i) {
    const TechniqueResult& r = in.trace.records[i];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    const std::string name = techniqueLabel(r.technique());
    if (ImGui::Selectable(name.c_str(), state.selected == static_cast<int>(i), ImGuiSelectableFlags_SpanAllColumns))
      state.selected = static_cast<int>(i);
    ImGui::TableNextColumn();
    if (r.blocked()) ImGui::TextColored(ImVec4(1.f, 0.4f, 0.4f, 1.f), "blocked");
    else if (isBlack(r.unweighted)) ImGui::TextDisabled("zero");
    else ImGui::Text("%.3g", luminance(r.unweighted));
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", r.weight);
    ImGui::TableNextColumn();
    if (isBlack(r.unweighted)) ImGui::TextDisabled("-");
    else ImGui::Text("%.3g", luminance(r.unweighted) * r.weight);
    ImGui::TableNextColumn();
    if (r.t == 1) ImGui::Text("%.0f,%.0f", r.pRaster.x, r.pRaster.y);
    else ImGui::TextDisabled("pixel");
  }
  ImGui::EndTable();
}

void drawEveryTechnique(PathInspectorState& state) {
  const SampleInspection& in = *state.result;
  // One path, every technique: the selected path's density and weights under each technique.
  if (state.selected >= 0 && static_cast<size_t>(state.selected) < in.trace.onPath.size()) {
    const TechniqueResult& r = in.trace.records[static_cast<size_t>(state.selected)];
    const std::vector<TechniqueOnPath>& every = in.trace.onPath[static_cast<size_t>(state.selected)];
    if (!every.empty()) {
      ImGui::TextWrapped("this path (length %d) under every technique of its length: its density p_A, the edge it "
                         "joins (the factors of f it does not sample) and its weights", r.technique().length());
      if (r.kind == TechniqueKind::Merge)
        ImGui::TextWrapped("merges light vertex x%d with the camera vertex %.3g away, within radius %.3g (the disk)",
                           r.s - 1, static_cast<double>(glm::length(r.merged.light - r.merged.camera)),
                           static_cast<double>(r.merged.radius));
      const float barWidth = ImGui::GetContentRegionAvail().x * 0.3f;
      for (const TechniqueOnPath& x : every) {
        const bool merge = x.kind == TechniqueKind::Merge;
        const std::string name = techniqueLabel(x.technique());
        ImGui::TextUnformatted(name.c_str());
        ImGui::SameLine(ImGui::GetFontSize() * 4.5f);
        if (!x.possible) {
          ImGui::TextDisabled(merge                    ? "cannot: no surface a merge can take there"
                              : x.connectionEdge < 0 ? "cannot: its light cannot be hit"
                              : x.t == 1           ? "cannot: a delta vertex or an orthographic camera"
                                                   : "cannot: a delta vertex");
          continue;
        }
        // Three thin bars stacked in one row's height: balance, power, uniform.
        const ImVec2 at = ImGui::GetCursorScreenPos();
        const float h = ImGui::GetTextLineHeight() / 3.f;
        ImDrawList* draw = ImGui::GetWindowDrawList();
        const double w[3] = {x.balance, x.power, x.uniform};
        const ImU32 colours[3] = {IM_COL32(90, 200, 255, 255), IM_COL32(255, 165, 60, 255), IM_COL32(180, 180, 180, 255)};
        for (int k = 0; k < 3; ++k) {
          const float y0 = at.y + static_cast<float>(k) * h;
          draw->AddRectFilled(ImVec2(at.x, y0), ImVec2(at.x + barWidth, y0 + h - 1.f), IM_COL32(50, 50, 56, 255));
          draw->AddRectFilled(ImVec2(at.x, y0), ImVec2(at.x + barWidth * static_cast<float>(std::clamp(w[k], 0.0, 1.0)), y0 + h - 1.f),
                              colours[k]);
        }
        ImGui::Dummy(ImVec2(barWidth, ImGui::GetTextLineHeight()));
        ImGui::SameLine();
        // What f's factors this technique leaves to chance: its connection edge (the geometry term
        // and the BSDFs at its ends are evaluated, not sampled).
        const std::string edge = merge                   ? fmt::format("merges at x{}", x.mergedVertex)
                                 : x.connectionEdge < 0 ? std::string("hits the light")
                                                        : fmt::format("joins x{}-x{}", x.connectionEdge, x.connectionEdge + 1);
        ImGui::Text("p_A %.3g  %s%s%s", x.pdfA, edge.c_str(), x.enabled ? "" : "  (off)",
                    x.technique() == r.technique() ? "  <" : "");
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("%s: p_A %.4g, balance %.4f, power %.4f, uniform %.4f%s", name.c_str(), x.pdfA, x.balance,
                            x.power, x.uniform,
                            merge ? ", merged within the radius (p_A: pi r^2 times its density from the camera side times "
                                    "the connection's)"
                            : x.connectionEdge < 0 ? ", hits the emitter" : "");
      }
      ImGui::TextWrapped("bars: balance (blue), power (orange), uniform (grey); < the technique that sampled it; x0 "
                         "on the light");
    }
  } else {
    ImGui::TextDisabled("select a technique on the left: its path under every technique of its length");
  }
}

}  // namespace

void drawInspectorWindow(PathInspectorState& state, PanelRect rect, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(rect.x, rect.y));
  ImGui::SetNextWindowSize(ImVec2(rect.width, rect.height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::Begin("Path inspector", nullptr, flags);
  if (!state.pixel) ImGui::TextDisabled("click the image to pick a pixel: its sample's subpaths, connections and techniques");
  if (!state.error.empty()) ImGui::TextColored(ImVec4(1.f, 0.7f, 0.3f, 1.f), "%s", state.error.c_str());
  if (state.result) {
    const SampleInspection& in = *state.result;
    ImGui::Text("pixel %d,%d  sample %llu", in.x, in.y, static_cast<unsigned long long>(in.sample));
    ImGui::SameLine();
    if (ImGui::SmallButton("< sample (B)")) requests.actions.push_back(Action::PreviousSample);
    ImGui::SameLine();
    if (ImGui::SmallButton("sample > (N)")) requests.actions.push_back(Action::NextSample);
    ImGui::SameLine();
    const std::string brightest = fmt::format("brightest of {} (H)", brightestSearchCount(state.inspectedSettings));
    if (ImGui::SmallButton(brightest.c_str())) requests.actions.push_back(Action::BrightestSample);
    ImGui::SameLine();
    if (ImGui::SmallButton("export JSON (Ctrl+J)")) requests.actions.push_back(Action::ExportInspection);
    ImGui::TextDisabled("camera subpath %d, light subpath %d vertices", in.trace.cameraVertices, in.trace.lightVertices);
    // The table on the left, the selected path under every technique on the right.
    const float half = 0.5f * ImGui::GetContentRegionAvail().x;
    ImGui::BeginChild("table", ImVec2(half, 0.f));
    drawTechniqueRows(state);
    ImGui::EndChild();
    ImGui::SameLine();
    ImGui::BeginChild("every", ImVec2(0.f, 0.f));
    drawEveryTechnique(state);
    ImGui::EndChild();
  }
  ImGui::End();
}

}  // namespace pathlab::ui
