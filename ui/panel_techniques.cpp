// The estimator section: integrator, maximum length, MIS heuristic, the combine / isolate mode and
// the technique grid laid out like Veach 1997, fig. 10.3 (rows: path length k = s + t - 1 edges;
// columns: s, the number of light subpath vertices).
#include "ui/viewer.h"

#include "ui/technique_grid.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

constexpr int kGridMaxLength = 10;  // longer techniques are edited through the SPEC
const ImVec4 kWarning(1.f, 0.7f, 0.2f, 1.f);
const ImVec4 kError(1.f, 0.35f, 0.35f, 1.f);

std::string techniqueTooltip(int s, int t) {
  const int k = s + t - 1;
  std::string what;
  if (s == 0) what = "the camera subpath hits an emitter by itself (path tracing without a light sample)";
  else if (t == 1 && s == 1) what = "a point on an emitter connected to the camera (the emitter seen directly, by light tracing)";
  else if (t == 1) what = "light tracing: the light subpath's last vertex connected to the camera, splatted on the film";
  else if (s == 1) what = "next event estimation: a light sample connected to the camera subpath";
  else what = fmt::format("light subpath vertex {} connected to camera subpath vertex {}", s, t);
  return fmt::format("(s,t) = ({},{}): {} light and {} camera vertices, path length {}\n{}", s, t, s, t, k, what);
}

}  // namespace

void Viewer::drawEstimatorSection() {
  ImGui::PushID("estimator");
  // Integrator
  int integrator = edited_.integrator == IntegratorKind::Bpt ? 0 : edited_.integrator == IntegratorKind::Pt ? 1 : 2;
  ImGui::TextUnformatted("integrator");
  ImGui::SameLine();
  ImGui::RadioButton("bpt", &integrator, 0);
  ImGui::SameLine();
  ImGui::RadioButton("pt", &integrator, 1);
  ImGui::SameLine();
  ImGui::RadioButton("lt", &integrator, 2);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("light tracing: only the t = 1 techniques");
  edited_.integrator = integrator == 0 ? IntegratorKind::Bpt : integrator == 1 ? IntegratorKind::Pt : IntegratorKind::Lt;

  int maxLength = edited_.maxLength;
  if (ImGui::SliderInt("max length", &maxLength, 1, 32)) {
    setMaxLength(edited_, maxLength);
    oneLength_ = std::min(oneLength_, edited_.maxLength);
    if (edited_.isolate) isolateS_ = edited_.isolate->s, isolateT_ = edited_.isolate->t;
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("maximum path length in edges: 1 shows emitters, 2 adds direct light");

  const bool bidirectional = edited_.integrator != IntegratorKind::Pt;
  ImGui::BeginDisabled(!bidirectional);

  // MIS heuristic
  int heuristic = static_cast<int>(edited_.mis.heuristic);
  ImGui::TextUnformatted("MIS");
  ImGui::SameLine();
  ImGui::RadioButton("balance", &heuristic, static_cast<int>(MisHeuristic::Balance));
  ImGui::SameLine();
  ImGui::RadioButton("power", &heuristic, static_cast<int>(MisHeuristic::Power));
  ImGui::SameLine();
  ImGui::RadioButton("uniform", &heuristic, static_cast<int>(MisHeuristic::Uniform));
  edited_.mis.heuristic = static_cast<MisHeuristic>(heuristic);
  if (edited_.mis.heuristic == MisHeuristic::Power) ImGui::SliderFloat("beta", &edited_.mis.beta, 0.5f, 8.f, "%.2f");
  ImGui::SliderFloat("min connection", &edited_.mis.minConnection, 0.f, 0.3f, "%.4f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("connections shorter than this fraction of the scene's radius are left to the techniques\n"
                      "that sample that edge (1/d^2 near corners); unbiased at any value, 0 turns it off.\n"
                      "Uniform weights gain most; balance and power barely notice.");

  // Mode
  int mode = static_cast<int>(modeOf(edited_));
  for (int m = 0; m < 3; ++m)
    if (ImGui::RadioButton(modeLabel(static_cast<EstimatorMode>(m)), &mode, m))
      setMode(edited_, static_cast<EstimatorMode>(m), isolateS_, isolateT_);
  if (edited_.isolate) {
    ImGui::Text("isolated technique (s,t) = (%d,%d), length %d", isolateS_, isolateT_, isolateS_ + isolateT_ - 1);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("click a cell of the grid or a pyramid thumbnail; arrow keys move it");
    if (isolatedTechniqueDisabled(edited_)) {
      ImGui::PushStyleColor(ImGuiCol_Text, kWarning);
      ImGui::TextWrapped("(%d,%d) is not enabled: its weighted share is zero (Ctrl+click enables it)", isolateS_,
                         isolateT_);
      ImGui::PopStyleColor();
    }
  }

  ImGui::Separator();
  drawTechniqueGrid();
  ImGui::EndDisabled();
  if (!bidirectional) ImGui::TextDisabled("the path tracer ignores the technique set");

  if (!settingsError_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("refused: %s", settingsError_.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopID();
}

void Viewer::drawTechniqueGrid() {
  const TechniqueSet& set = edited_.techniques;
  const bool isolating = edited_.isolate.has_value();
  const bool lightTracing = edited_.integrator == IntegratorKind::Lt;
  const int rows = std::min(edited_.maxLength, kGridMaxLength);

  // Presets
  auto presetButton = [&](const char* label, TechniquePreset preset, const char* key) {
    if (ImGui::SmallButton(label)) edited_.techniques = presetTechniques(preset, oneLength_);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (key %s)", presetLabel(preset), key);
  };
  presetButton("all", TechniquePreset::All, "1");
  ImGui::SameLine();
  presetButton("s<=1 (PT)", TechniquePreset::PathTracing, "2");
  ImGui::SameLine();
  presetButton("t=1 (LT)", TechniquePreset::LightTracing, "3");
  ImGui::SameLine();
  presetButton("clear", TechniquePreset::Clear, "0");
  presetButton("only length", TechniquePreset::OneLength, "4");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
  // Moving the length while "only length" is active moves the selection with it.
  const bool oneLengthActive = edited_.techniques == presetTechniques(TechniquePreset::OneLength, oneLength_);
  if (ImGui::SliderInt("##onelength", &oneLength_, 1, edited_.maxLength, "k = %d") && oneLengthActive)
    edited_.techniques = presetTechniques(TechniquePreset::OneLength, oneLength_);

  // The grid: one checkbox per (s,t); in the isolate modes a click picks the isolated technique.
  const ImGuiTableFlags flags = ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_NoHostExtendX;
  if (ImGui::BeginTable("grid", rows + 2, flags)) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextDisabled("k\\s");
    for (int s = 0; s <= rows; ++s) {
      ImGui::TableSetColumnIndex(s + 1);
      ImGui::PushID(1000 + s);
      // A column header switches every technique with this s.
      if (ImGui::SmallButton(fmt::format("{}", s).c_str()) && !isolating)
        edited_.techniques = toggleLightVertices(set, edited_.maxLength, s);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("s = %d: every technique with %d light vertices on/off", s, s);
      ImGui::PopID();
    }
    for (int k = 1; k <= rows; ++k) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::PushID(2000 + k);
      // A row label switches every technique of this length.
      if (ImGui::SmallButton(fmt::format("{}", k).c_str()) && !isolating)
        edited_.techniques = toggleLength(set, edited_.maxLength, k);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("length %d: every technique on/off", k);
      ImGui::PopID();
      for (const auto [s, t] : techniquesOfLength(k)) {
        ImGui::TableSetColumnIndex(s + 1);
        ImGui::PushID(k * 100 + s);
        const bool isolated = isolating && s == isolateS_ && t == isolateT_;
        if (isolated) ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(230, 160, 40, 200));
        ImGui::BeginDisabled(lightTracing && t != 1);
        bool on = set.contains(s, t);
        if (ImGui::Checkbox("##t", &on)) {
          // Isolating, a click picks the technique shown; Ctrl+click still switches it on or off
          // (a weighted share depends on which techniques are enabled).
          if (isolating && !ImGui::GetIO().KeyCtrl) {
            setIsolateTarget(s, t);
          } else {
            edited_.techniques = toggleTechnique(set, edited_.maxLength, {s, t});
          }
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
          const TechniqueCounters& c = snapshot_.counters.technique(s, t);
          ImGui::SetTooltip("%s\nthis generation: %llu connections tried, %llu blocked, %llu contributed, %llu discarded",
                            techniqueTooltip(s, t).c_str(), static_cast<unsigned long long>(c.tried),
                            static_cast<unsigned long long>(c.blocked), static_cast<unsigned long long>(c.contributed),
                            static_cast<unsigned long long>(c.discarded.total()));
        }
        ImGui::PopID();
      }
    }
    ImGui::EndTable();
  }
  if (edited_.maxLength > kGridMaxLength)
    ImGui::TextDisabled("lengths %d..%d: edit the SPEC", kGridMaxLength + 1, edited_.maxLength);

  // The SPEC as text (as --techniques takes it); applied on Enter.
  // A SPEC that does not parse never reaches the settings: its error shows under the field.
  std::string spec = edited_.techniques.toString();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.7f);
  if (ImGui::InputText("SPEC", &spec, ImGuiInputTextFlags_EnterReturnsTrue)) {
    try {
      edited_.techniques = parseTypedSpec(spec, edited_.maxLength);
      specError_.clear();
    } catch (const std::invalid_argument& e) {
      specError_ = e.what();
    }
  }
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("';'-separated S,T | s=S | t=T | k=K | all; Enter applies");
  if (!specError_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("%s", specError_.c_str());
    ImGui::PopStyleColor();
  }

  // Lengths no enabled technique can sample: their light is missing from the image.
  const TechniqueSet enabled = enabledTechniques(edited_);
  if (const std::vector<int> uncovered = enabled.uncoveredLengths(edited_.maxLength);
      !uncovered.empty() && enabled.anyUpTo(edited_.maxLength)) {
    std::string list;
    for (int k : uncovered) list += (list.empty() ? "" : ", ") + std::to_string(k);
    ImGui::PushStyleColor(ImGuiCol_Text, kWarning);
    ImGui::TextWrapped("no enabled technique samples paths of length %s: that light is missing", list.c_str());
    ImGui::PopStyleColor();
  } else if (!enabled.anyUpTo(edited_.maxLength)) {
    ImGui::PushStyleColor(ImGuiCol_Text, kWarning);
    ImGui::TextWrapped("no technique enabled: nothing is rendered");
    ImGui::PopStyleColor();
  }
}

}  // namespace pathlab::ui
