// The estimator section: integrator, maximum length, MIS heuristic, the combine / isolate mode and
// the technique grid laid out like Veach 1997, fig. 10.3 (rows: path length k = s + t - 1 edges;
// columns: s, the number of light subpath vertices).
#include "ui/panels/panels.h"

#include "core/bpt/merge_pass.h"
#include "core/bpt/optimal_mis.h"
#include "core/bpt/variance_aware_mis.h"
#include "core/sampling/technique_label.h"
#include "ui/estimator/technique_grid.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace pathlab::ui {

namespace {

constexpr int kGridMaxLength = 10;  // longer techniques are edited through the SPEC
const ImVec4 kTechniqueWarning(1.f, 0.7f, 0.2f, 1.f);
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

std::string mergeTooltip(Technique x) {
  return fmt::format("M({},{}): light subpath vertex {} merged with camera subpath vertex {} within the pass's radius "
                     "(vertex merging), path length {}",
                     x.s, x.t, x.s, x.t, x.length());
}

// The grid: one checkbox per (s,t), rows by length, columns by s, each length's merges in a row of
// their own under its connections; its presets and the SPEC field.
const TechniqueVerdict* verdictOf(const CheckReport* check, Technique x) {
  if (!check) return nullptr;
  for (const TechniqueVerdict& v : check->techniques)
    if (v.technique == x) return &v;
  return nullptr;
}

std::string verdictText(const TechniqueVerdict& v, int blocks) {
  if (v.status != CheckStatus::Agrees && v.status != CheckStatus::Disagrees)
    return fmt::format("check: {}", checkStatusName(v.status));
  const std::string region = v.worstRegion == TechniqueCheck::wholeImage(blocks)
                                 ? std::string("the whole image")
                                 : fmt::format("block ({},{})", v.worstRegion % blocks, v.worstRegion / blocks);
  return fmt::format("check: {} (z = {:+.2f} against {} in {}, whole image z = {:+.2f})", checkStatusName(v.status),
                     v.z, techniqueLabel(v.worst.partner), region, v.wholeImageZ);
}

void drawTechniqueGrid(EstimatorState& estimator, TechniqueGridState& grid, const Counters& counters,
                       const CheckReport* check, TechniqueFamilies sampled) {
  RenderSettings& edited = estimator.settings;
  const TechniqueSet& set = edited.techniques;
  const bool isolating = estimator.mode != EstimatorMode::Combine;
  const int oneLength = std::min(grid.oneLength, edited.maxLength);
  const bool lightTracing = edited.integrator == IntegratorKind::Lt;
  const int rows = std::min(edited.maxLength, kGridMaxLength);
  const bool showMerges = covers(set.families(), TechniqueKind::Merge);
  // The equiangular techniques E(1, k) in a column of their own, where bpt samples them in this
  // scene (sampledFamilies: a medium they can sample, --medium-sampling mis or equiangular).
  const bool showEquiangular = covers(sampled, TechniqueKind::Equiangular);

  // Presets
  auto presetButton = [&](const char* label, TechniquePreset preset, const char* key) {
    if (ImGui::SmallButton(label)) edited.techniques = presetTechniques(preset, oneLength);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (key %s)", presetLabel(preset), key);
  };
  presetButton("all", TechniquePreset::All, "1");
  ImGui::SameLine();
  presetButton("s<=1 (PT)", TechniquePreset::PathTracing, "2");
  ImGui::SameLine();
  presetButton("t=1 (LT)", TechniquePreset::LightTracing, "3");
  ImGui::SameLine();
  presetButton("clear", TechniquePreset::Clear, "0");
  ImGui::SameLine();
  // Vertex connection and merging: every merge added to (or taken from) what is enabled.
  if (ImGui::SmallButton("+merges (VCM)") && !isolating && edited.integrator == IntegratorKind::Bpt)
    edited.techniques = toggleAllMerges(set, edited.maxLength);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("every merging technique M(s,t) on or off (vertex merging; --techniques \"all;m=all\" is VCM)");
  if (showEquiangular) {
    if (ImGui::SmallButton("E(1,k) on/off") && !isolating) edited.techniques = toggleEquiangular(set, edited.maxLength);
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("every equiangular technique E(1,k) on/off (the green cells): C(1,k)'s path with its camera\n"
                        "vertex next to the light placed in the medium toward a point on the light (Kulla and\n"
                        "Fajardo 2012)");
  }
  presetButton("only length", TechniquePreset::OneLength, "4");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
  // Moving the length while "only length" is active moves the selection with it.
  const bool oneLengthActive = edited.techniques == presetTechniques(TechniquePreset::OneLength, oneLength);
  grid.oneLength = oneLength;
  if (ImGui::SliderInt("##onelength", &grid.oneLength, 1, edited.maxLength, "k = %d") && oneLengthActive)
    edited.techniques = presetTechniques(TechniquePreset::OneLength, grid.oneLength);

  // The grid: one checkbox per (s,t); in the isolate modes a click picks the isolated technique.
  const ImGuiTableFlags flags = ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_NoHostExtendX;
  // With E, one column more: E(1, k) sits at column s = k + 1 of its row.
  if (ImGui::BeginTable("grid", rows + (showEquiangular ? 3 : 2), flags)) {
    ImGui::TableNextRow();
    ImGui::TableSetColumnIndex(0);
    ImGui::TextDisabled("k\\s");
    for (int s = 0; s <= rows; ++s) {
      ImGui::TableSetColumnIndex(s + 1);
      ImGui::PushID(1000 + s);
      // A column header switches every technique with this s.
      if (ImGui::SmallButton(fmt::format("{}", s).c_str()) && !isolating)
        edited.techniques = toggleLightVertices(set, edited.maxLength, s);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("s = %d: every technique with %d light vertices on/off", s, s);
      ImGui::PopID();
    }

    for (int k = 1; k <= rows; ++k) {
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::PushID(2000 + k);
      // A row label switches every technique of this length.
      if (ImGui::SmallButton(fmt::format("{}", k).c_str()) && !isolating)
        edited.techniques = toggleLength(set, edited.maxLength, k);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("length %d: every technique on/off", k);
      ImGui::PopID();
      for (const Technique x : techniquesOfLength(k)) {
        const int s = x.s, t = x.t;
        ImGui::TableSetColumnIndex(s + 1);
        ImGui::PushID(k * 100 + s);
        const bool isolated = isolating && estimator.isolated == Technique{s, t};
        if (isolated) ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(230, 160, 40, 200));
        const TechniqueVerdict* verdict = verdictOf(check, {s, t});
        if (verdict && verdict->status == CheckStatus::Disagrees)
          ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(220, 40, 40, 230));
        ImGui::BeginDisabled(lightTracing && t != 1);
        // The grid ticks what the integrator really uses (techniqueShownEnabled).
        bool on = techniqueShownEnabled(edited, {s, t});
        if (ImGui::Checkbox("##t", &on) && edited.integrator != IntegratorKind::Pt) {
          // Isolating, a click picks the technique shown; Ctrl+click still switches it on or off
          // (a weighted share depends on which techniques are enabled).
          if (isolating && !ImGui::GetIO().KeyCtrl) {
            setIsolated(estimator, {s, t});
          } else {
            edited.techniques = toggleTechnique(set, edited.maxLength, {s, t});
          }
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
          const TechniqueCounters& c = counters.technique(s, t);
          ImGui::SetTooltip("%s\nthis generation: %llu connections tried, %llu blocked, %llu contributed, %llu discarded%s",
                            techniqueTooltip(s, t).c_str(), static_cast<unsigned long long>(c.tried),
                            static_cast<unsigned long long>(c.blocked), static_cast<unsigned long long>(c.contributed),
                            static_cast<unsigned long long>(c.discarded.total()),
                            verdict ? ("\n" + verdictText(*verdict, check->blocks)).c_str() : "");
        }
        ImGui::PopID();
      }
      // E(1, k) just right of its length's last connection (k, 1), on a green cell: the E's run
      // down beside the pyramid's diagonal, as in the pyramid window.
      if (showEquiangular && k >= 2) {
        const Technique x = Technique::equiangular(k);
        ImGui::TableSetColumnIndex(k + 2);
        ImGui::PushID(k * 100 + 99);
        ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, isolating && estimator.isolated == x
                                                              ? IM_COL32(230, 160, 40, 200)
                                                              : IM_COL32(0, 136, 86, 110));
        const TechniqueVerdict* verdict = verdictOf(check, x);
        if (verdict && verdict->status == CheckStatus::Disagrees)
          ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(220, 40, 40, 230));
        bool on = techniqueShownEnabled(edited, x);
        if (ImGui::Checkbox("##e", &on)) {
          if (isolating && !ImGui::GetIO().KeyCtrl) {
            setIsolated(estimator, x);
          } else {
            edited.techniques = toggleTechnique(set, edited.maxLength, x);
          }
        }
        if (ImGui::IsItemHovered()) {
          const TechniqueCounters& c = counters.technique(x);
          ImGui::SetTooltip("E(1,%d): the path of C(1,%d) with its camera vertex next to the light placed in the\n"
                            "medium by equiangular sampling toward the light point\n"
                            "this generation: %llu tried, %llu blocked, %llu contributed%s",
                            k, k, static_cast<unsigned long long>(c.tried), static_cast<unsigned long long>(c.blocked),
                            static_cast<unsigned long long>(c.contributed),
                            verdict ? ("\n" + verdictText(*verdict, check->blocks)).c_str() : "");
        }
        ImGui::PopID();
      }
      // The merges of this length, M(s, k + 2 - s) under column s = 2..k, when the set has any.
      if (k < 2 || !showMerges) continue;
      ImGui::TableNextRow();
      ImGui::TableSetColumnIndex(0);
      ImGui::PushID(3000 + k);
      if (ImGui::SmallButton(fmt::format("M{}", k).c_str()) && !isolating)
        edited.techniques = toggleMergesOfLength(set, edited.maxLength, k);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("length %d: every merge on/off", k);
      ImGui::PopID();
      for (const Technique x : techniquesOfLength(k, TechniqueFamilies::Merges)) {
        ImGui::TableSetColumnIndex(x.s + 1);
        ImGui::PushID(k * 100 + 50 + x.s);
        if (isolating && estimator.isolated == x)
          ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(230, 160, 40, 200));
        const TechniqueVerdict* verdict = verdictOf(check, x);
        if (verdict && verdict->status == CheckStatus::Disagrees)
          ImGui::TableSetBgColor(ImGuiTableBgTarget_CellBg, IM_COL32(220, 40, 40, 230));
        ImGui::BeginDisabled(lightTracing);
        bool on = techniqueShownEnabled(edited, x);
        if (ImGui::Checkbox("##m", &on) && edited.integrator == IntegratorKind::Bpt) {
          // As for a connection: isolating, a click picks the merge shown; Ctrl+click switches it.
          if (isolating && !ImGui::GetIO().KeyCtrl) {
            setIsolated(estimator, x);
          } else {
            edited.techniques = toggleTechnique(set, edited.maxLength, x);
          }
        }
        ImGui::EndDisabled();
        if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) {
          const TechniqueCounters& c = counters.technique(x);
          ImGui::SetTooltip("%s\nthis generation: %llu merges tried, %llu contributed%s", mergeTooltip(x).c_str(),
                            static_cast<unsigned long long>(c.tried), static_cast<unsigned long long>(c.contributed),
                            verdict ? ("\n" + verdictText(*verdict, check->blocks)).c_str() : "");
        }
        ImGui::PopID();
      }
    }
    ImGui::EndTable();
  }
  if (edited.maxLength > kGridMaxLength)
    ImGui::TextDisabled("lengths %d..%d: edit the SPEC", kGridMaxLength + 1, edited.maxLength);

  // The SPEC as text (as --techniques takes it); applied on Enter.
  // A SPEC that does not parse never reaches the settings: its error shows under the field.
  std::string spec = edited.techniques.toString();
  ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.7f);
  if (ImGui::InputText("SPEC", &spec, ImGuiInputTextFlags_EnterReturnsTrue)) {
    try {
      edited.techniques = parseTypedSpec(spec, edited.maxLength);
      grid.specError.clear();
    } catch (const std::invalid_argument& e) {
      grid.specError = e.what();
    }
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("';'-separated S,T | s=S | t=T | k=K | all, merges MS,T | m=K | m=all; Enter applies");
  if (!grid.specError.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("%s", grid.specError.c_str());
    ImGui::PopStyleColor();
  }

  // Lengths no enabled technique can sample: their light is missing from the image.
  const TechniqueSet enabled = enabledTechniques(edited);
  if (const std::vector<int> uncovered = enabled.uncoveredLengths(edited.maxLength);
      !uncovered.empty() && enabled.anyUpTo(edited.maxLength)) {
    std::string list;
    for (int k : uncovered) list += (list.empty() ? "" : ", ") + std::to_string(k);
    ImGui::PushStyleColor(ImGuiCol_Text, kTechniqueWarning);
    ImGui::TextWrapped("no enabled technique samples paths of length %s: that light is missing", list.c_str());
    ImGui::PopStyleColor();
  } else if (!enabled.anyUpTo(edited.maxLength)) {
    ImGui::PushStyleColor(ImGuiCol_Text, kTechniqueWarning);
    ImGui::TextWrapped("no technique enabled: nothing is rendered");
    ImGui::PopStyleColor();
  }
}

}  // namespace

// The consistency check (issue 13, part 4): on/off, its verdict, the |z| map's technique, and a
// deliberately wrong technique (inject bias) to see what the check and the image make of one.
void drawCheckControls(EstimatorState& estimator, TechniqueGridState& grid, const CheckReport* check) {
  RenderSettings& edited = estimator.settings;
  const bool combining = estimator.mode == EstimatorMode::Combine;
  ImGui::BeginDisabled(!combining);
  ImGui::Checkbox("check techniques", &edited.checkTechniques);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("compare every enabled technique's unweighted estimate with the others' on the paths both can\n"
                      "sample (per %d x %d blocks and the whole image); a technique that disagrees turns red.\n"
                      "Runs while combining (isolation renders one technique only); `pathlab check` on the CLI.",
                      edited.checkBlocks, edited.checkBlocks);
  if (edited.checkTechniques && combining) {
    ImGui::SameLine();
    if (!check) {
      ImGui::TextDisabled("(waiting for passes)");
    } else if (check->agrees()) {
      ImGui::TextColored(ImVec4(0.4f, 0.9f, 0.4f, 1.f), "all agree (%llu passes)", static_cast<unsigned long long>(check->passes));
    } else {
      ImGui::TextColored(kError, "%d disagree", check->disagreeing());
    }
    std::string current = grid.zMap ? techniqueLabel(*grid.zMap) : std::string("off");
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.5f);
    if (ImGui::BeginCombo("|z| map", current.c_str())) {
      if (ImGui::Selectable("off", !grid.zMap)) grid.zMap.reset();
      if (check)
        for (const TechniqueVerdict& v : check->techniques) {
          const std::string label =
              techniqueLabel(v.technique) + (v.status == CheckStatus::Disagrees ? "  disagrees" : "");
          if (ImGui::Selectable(label.c_str(), grid.zMap == v.technique)) grid.zMap = v.technique;
        }
      ImGui::EndCombo();
    }
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("draw the technique's |z| per block over the image");
  }
  bool inject = edited.injectBias.has_value();
  if (ImGui::Checkbox("inject bias", &inject))
    edited.injectBias = inject ? std::optional<BiasInjection>(BiasInjection{1, 2, 1.05f}) : std::nullopt;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("multiply one technique's unweighted contribution by a factor: a deliberate bug that biases\n"
                      "the image (named in the caption and the status) and that the check should find");
  if (edited.injectBias) {
    BiasInjection& b = *edited.injectBias;
    int st[2] = {b.s, b.t};
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.35f);
    if (ImGui::InputInt2("(s,t)##bias", st) && Technique{st[0], st[1]}.valid() &&
        Technique{st[0], st[1]}.length() <= edited.maxLength)
      b.s = st[0], b.t = st[1];
    ImGui::SameLine();
    ImGui::SetNextItemWidth(ImGui::GetContentRegionAvail().x * 0.6f);
    ImGui::SliderFloat("factor##bias", &b.factor, 0.f, 2.f, "%.3f");
  }
}

namespace {

// Vertex merging's parameters, shown while the set has merges: the first pass's radius and its
// schedule (--radius, --radius-alpha), where the camera subpath merges (ppm), the share of
// non-caustic light vertices kept (--noncaustic-photons), and the radius the shown image's last
// pass used.
void drawMergeControls(RenderSettings& edited, const MergeRadiusNow& now) {
  if (!covers(enabledTechniques(edited).families(), TechniqueKind::Merge)) return;
  ImGui::Separator();
  ImGui::TextUnformatted("vertex merging");
  // Unset until moved: the radius then follows the image size (firstMergeRadius).
  float radius = firstMergeRadius(edited);
  if (ImGui::SliderFloat("radius", &radius, 1e-4f, kMaxMergeRadius, "%.4g", ImGuiSliderFlags_Logarithmic))
    edited.mergeRadius = radius;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("r1, the first pass's merge radius, as a fraction of the scene's bounding radius (--radius):\n"
                      "larger merges more light vertices (less noise) over a wider disk (more blur, more bias).\n"
                      "Until moved it follows the image size: 0.003 at 512 x 512, times 512 / sqrt(pixels)");
  ImGui::SliderFloat("radius alpha", &edited.mergeRadiusAlpha, 0.05f, 1.f, "%.2f");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("pass i merges within r_i = r1 i^((alpha - 1) / 2) (--radius-alpha): the bias vanishes as passes\n"
                      "add up; 1 keeps r1 (biased for ever), smaller shrinks faster (noisier)");
  bool firstOnly = edited.mergeSite == MergeSite::FirstNonSpecular;
  ImGui::Checkbox("ppm: merge at the first non-specular vertex", &firstOnly);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("progressive photon mapping's estimator: the camera subpath merges once, where it first meets\n"
                      "a surface that is not a mirror or glass; off, it merges at every such vertex (VCM, BPM)");
  edited.mergeSite = firstOnly ? MergeSite::FirstNonSpecular : MergeSite::Every;
  // Unset until moved: the share then follows the set (mergeNonCaustic).
  float nonCaustic = mergeNonCaustic(edited);
  if (ImGui::SliderFloat("non-caustic", &nonCaustic, kMinMergeNonCaustic, 1.f, "%.3g",
                         ImGuiSliderFlags_Logarithmic))
    edited.mergeNonCaustic = nonCaustic;
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the share of light vertices not reached through a mirror or glass that a pass keeps for\n"
                      "merging, each kept one standing for 1/share (--noncaustic-photons); caustic ones are always\n"
                      "kept. 1 is VCM as published; less costs less where connections already do well");
  const RenderSettings* shown = now.shown;
  if (shown && now.passes > 0 && covers(enabledTechniques(*shown).families(), TechniqueKind::Merge))
    ImGui::TextDisabled("pass %llu: r = %.3g (scene radius %.3g)", static_cast<unsigned long long>(now.passes),
                        static_cast<double>(mergeRadius(firstMergeRadius(*shown) * now.sceneRadius, shown->mergeRadiusAlpha,
                                                        now.passes - 1)),
                        static_cast<double>(now.sceneRadius));
}

// Metropolis (issue 33): the variant, the mutation's two parameters, the chains and bootstrap, and
// what the last pass's chains did.
// Multiplexed chains: for each length with chains, each technique's share of its proposals and
// the acceptance of those proposals (the state's first number picks the technique, so a technique
// whose paths the target favours is accepted more often and the chain spends longer in it).
void drawAcceptanceByTechnique(const MltSummary& now) {
  const MltStats& s = now.stats;
  if (s.proposedByTechnique.empty() || !ImGui::TreeNode("acceptance by technique")) return;
  int widest = 0;
  for (size_t k = 1; k < now.chainsByLength.size(); ++k)
    if (now.chainsByLength[k] > 0) widest = static_cast<int>(k);
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_SizingFixedFit | ImGuiTableFlags_ScrollX;
  int rows = 0;
  for (size_t k = 1; k <= static_cast<size_t>(widest); ++k) rows += now.chainsByLength[k] > 0;
  // The header and the rows, each a line and its cell padding, and the horizontal scroll bar.
  const ImGuiStyle& style = ImGui::GetStyle();
  const ImVec2 size(0.f, static_cast<float>(rows + 1) * (ImGui::GetTextLineHeight() + 2.f * style.CellPadding.y + 1.f) +
                             style.ScrollbarSize + 2.f);
  if (widest > 0 && ImGui::BeginTable("acceptance", widest + 2, flags, size)) {
    ImGui::TableSetupColumn("k", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("00").x);
    const float cell = ImGui::CalcTextSize("100% of 100%").x;
    for (int sIndex = 0; sIndex <= widest; ++sIndex)
      ImGui::TableSetupColumn(fmt::format("s={}", sIndex).c_str(), ImGuiTableColumnFlags_WidthFixed, cell);
    ImGui::TableHeadersRow();
    for (int k = 1; k <= widest; ++k) {
      if (now.chainsByLength[static_cast<size_t>(k)] == 0) continue;
      const uint64_t all = s.proposedByLength[static_cast<size_t>(k)];
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d", k);
      for (int sIndex = 0; sIndex <= k; ++sIndex) {
        ImGui::TableNextColumn();
        const size_t x = Technique{sIndex, k + 1 - sIndex}.index();
        const uint64_t p = x < s.proposedByTechnique.size() ? s.proposedByTechnique[x] : 0;
        const uint64_t a = x < s.acceptedByTechnique.size() ? s.acceptedByTechnique[x] : 0;
        if (p == 0) {
          ImGui::TextDisabled("-");
          continue;
        }
        ImGui::Text("%.0f%% of %.0f%%", 100.0 * static_cast<double>(a) / static_cast<double>(p),
                    all ? 100.0 * static_cast<double>(p) / static_cast<double>(all) : 0.0);
        if (ImGui::IsItemHovered())
          ImGui::SetTooltip("(%d,%d): %.1f %% of length %d's proposals, %.1f %% of them accepted", sIndex, k + 1 - sIndex,
                            all ? 100.0 * static_cast<double>(p) / static_cast<double>(all) : 0.0, k,
                            100.0 * static_cast<double>(a) / static_cast<double>(p));
      }
    }
    ImGui::EndTable();
  }
  ImGui::TreePop();
}

void drawMetropolisControls(MltOptions& m, int maxLength, bool& showDensity, const MltSummary* now) {
  int variant = static_cast<int>(m.variant);
  ImGui::TextUnformatted("chains");
  ImGui::SameLine();
  ImGui::RadioButton("multiplexed", &variant, static_cast<int>(MltVariant::Multiplexed));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("MMLT (Hachisuka et al. 2014): a chain per path length; its state also picks the technique (s,t)");
  ImGui::SameLine();
  ImGui::RadioButton("primary space", &variant, static_cast<int>(MltVariant::PrimarySpace));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("PSSMLT (Kelemen et al. 2002): the state is a whole bidirectional sample, all techniques by MIS");
  m.variant = static_cast<MltVariant>(variant);
  ImGui::SliderFloat("large step", &m.largeStep, 0.f, 1.f, "%.2f");
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the probability of a large step: a new, independent path");
  ImGui::SliderFloat("sigma", &m.sigma, 0.001f, 0.3f, "%.3f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("a small step moves every primary number by a normal of this deviation");
  ImGui::SliderInt("chains##count", &m.chains, 1, 10000, "%d", ImGuiSliderFlags_Logarithmic);
  int bootstrap = static_cast<int>(std::min<uint64_t>(m.bootstrap, 1000000));
  if (ImGui::SliderInt("bootstrap", &bootstrap, 1000, 1000000, "%d", ImGuiSliderFlags_Logarithmic))
    m.bootstrap = static_cast<uint64_t>(std::max(bootstrap, 1));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("independent samples per path length that estimate b (the image's brightness) and start the\n"
                      "chains; every large step refines b as the chains run");
  ImGui::SliderInt("BPT up to", &m.directLength, 0, maxLength, m.directLength ? "%d edges" : "none");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("paths of up to this many edges (1: lights seen directly, 2: direct lighting) rendered by BPT,\n"
                      "one sample a pixel a pass, beside chains that explore only the longer ones (--mlt-direct)");
  ImGui::Checkbox("where the chains spend their time", &showDensity);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("over the image, each pixel's share of the chains' time relative to an even spread (viridis,\n"
                      "log scale: 1/100 dark blue, 1 green, 100 yellow; black: never). The image's brightness is b\n"
                      "times this density, length by length: the chains stay where the paths carry light");
  if (!now) return;
  const MltStats& s = now->stats;
  const double b = now->b;
  ImGui::Text("b = %.4g +- %.2f %%   acceptance %.1f %%", b, b > 0 ? 100.0 * now->bError / b : 0.0, 100.0 * s.acceptance());
  ImGui::Text("large steps: %.1f %% accepted",
              s.largeProposed ? 100.0 * static_cast<double>(s.largeAccepted) / static_cast<double>(s.largeProposed) : 0.0);
  if (now->directLength > 0)
    ImGui::Text("up to %d edges by BPT: %llu samples a pixel", now->directLength,
                static_cast<unsigned long long>(now->directSamples));
  if (m.variant != MltVariant::Multiplexed) return;
  std::string line = "chains by length:";
  for (size_t k = 1; k < now->chainsByLength.size(); ++k) {
    const uint64_t p = k < s.proposedByLength.size() ? s.proposedByLength[k] : 0;
    const uint64_t a = k < s.acceptedByLength.size() ? s.acceptedByLength[k] : 0;
    if (now->chainsByLength[k] == 0) continue;
    line += fmt::format(" {}: {} ({:.0f} %)", k, now->chainsByLength[k],
                        p ? 100.0 * static_cast<double>(a) / static_cast<double>(p) : 0.0);
  }
  ImGui::TextWrapped("%s", line.c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("length k: the chains that sample it (in proportion to its share of b), and their acceptance");
  drawAcceptanceByTechnique(*now);
}

}  // namespace

void drawEstimatorSection(EstimatorState& estimator, TechniqueGridState& grid, const std::string& settingsError,
                          const Counters& counters, const CheckReport* check, const MltSummary* mlt,
                          const MergeRadiusNow& radiusNow, TechniqueFamilies sampled,
                          const LightPathStatus* lightPaths) {
  RenderSettings& edited = estimator.settings;
  ImGui::PushID("estimator");
  // Integrator
  constexpr IntegratorKind kOrder[] = {IntegratorKind::Bpt, IntegratorKind::Pt, IntegratorKind::Lt, IntegratorKind::Mlt};
  int integrator = static_cast<int>(std::find(std::begin(kOrder), std::end(kOrder), edited.integrator) - std::begin(kOrder));
  ImGui::TextUnformatted("integrator");
  ImGui::SameLine();
  ImGui::RadioButton("bpt", &integrator, 0);
  ImGui::SameLine();
  ImGui::RadioButton("pt", &integrator, 1);
  ImGui::SameLine();
  ImGui::RadioButton("lt", &integrator, 2);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("light tracing: only the t = 1 techniques");
  ImGui::SameLine();
  ImGui::RadioButton("mlt", &integrator, 3);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Metropolis light transport: Markov chains over the enabled techniques (connections), in\n"
                      "proportion to what each path brings to the image");
  edited.integrator = kOrder[std::clamp(integrator, 0, 3)];
  if (edited.integrator == IntegratorKind::Mlt) {
    estimator.mode = EstimatorMode::Combine;  // the chains weigh every enabled technique: nothing isolated
    drawMetropolisControls(edited.mlt, edited.maxLength, estimator.showChainDensity, mlt);
  }

  int maxLength = edited.maxLength;
  if (ImGui::SliderInt("max length", &maxLength, 1, 32)) setMaxLength(estimator, maxLength);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("maximum path length in edges: 1 shows emitters, 2 adds direct light");

  // Media (issue 35): how the path tracer places the medium vertex it connects to a light; in bpt
  // (path reuse, no merges) whether the equiangular technique family E(1, k) joins the connections.
  const bool pt = edited.integrator == IntegratorKind::Pt;
  const bool equiangularBpt = edited.integrator == IntegratorKind::Bpt && edited.connect == ConnectStrategy::All &&
                              !covers(enabledTechniques(edited).families(), TechniqueKind::Merge);
  if (pt || equiangularBpt) {
    const MediumSampling now = mediumSampling(edited);
    int m = static_cast<int>(now);
    ImGui::TextUnformatted("in media");
    ImGui::SameLine();
    ImGui::RadioButton("distance", &m, static_cast<int>(MediumSampling::Distance));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(pt ? "the vertex placed along the transmittance (--medium-sampling distance)"
                           : "the connections alone: every medium vertex placed along the transmittance (bpt's default)");
    ImGui::SameLine();
    ImGui::RadioButton("equiangular", &m, static_cast<int>(MediumSampling::Equiangular));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(pt ? "the vertex placed toward a point on a light, density 1 / distance^2 (Kulla and Fajardo 2012)"
                           : "E(1,k) in place of C(1,k) on every path it can sample: the camera vertex next to the\n"
                             "light placed toward a point on it (Kulla and Fajardo 2012)");
    ImGui::SameLine();
    ImGui::RadioButton("MIS##medium", &m, static_cast<int>(MediumSampling::Mis));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(pt ? "both, weighted by the power heuristic: the path tracer's default. Scenes with scattering\n"
                             "media only; the same image every way, the noise around lights differs"
                           : "the equiangular techniques E(1,k) beside the connections, in the same MIS weights.\n"
                             "Scenes with homogeneous scattering media only: the grid's E column switches each");
    if (m != static_cast<int>(now)) edited.mediumSampling = static_cast<MediumSampling>(m);
  } else if (edited.mediumSampling && *edited.mediumSampling != MediumSampling::Distance) {
    edited.mediumSampling.reset();  // lt, mlt, merges and naive BPT sample distances only, so far
  }

  const bool bidirectional = edited.integrator != IntegratorKind::Pt;
  ImGui::BeginDisabled(!bidirectional);

  if (!bidirectional) {
    // The path tracer's own combination, not the bidirectional heuristic it does not use.
    ImGui::TextWrapped("MIS: power heuristic (beta 2), its light sample against BSDF sampling");
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
    ImGui::TextWrapped("the grid shows its techniques: s = 0 (BSDF sampling hits a light) and s = 1 (light sample)");
    ImGui::PopStyleColor();
  }
  // MIS heuristic (bpt and lt only: the path tracer's is fixed, above)
  int heuristic = static_cast<int>(edited.mis.heuristic);
  if (bidirectional) {
    ImGui::TextUnformatted("MIS");
    ImGui::SameLine();
    ImGui::RadioButton("balance", &heuristic, static_cast<int>(MisHeuristic::Balance));
    ImGui::SameLine();
    ImGui::RadioButton("power", &heuristic, static_cast<int>(MisHeuristic::Power));
    ImGui::SameLine();
    ImGui::RadioButton("uniform", &heuristic, static_cast<int>(MisHeuristic::Uniform));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("1 / (number of enabled techniques able to sample the path): unbiased");
    ImGui::SameLine();
    ImGui::RadioButton("off", &heuristic, static_cast<int>(MisHeuristic::Off));
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("1 / n_k for every enabled technique of length k, whatever the path (Veach's naive\n"
                        "combination): biased where a technique cannot sample a path (the status says where)");
    // Its own line: the panel is narrow.
    ImGui::SetCursorPosX(ImGui::GetCursorPosX() + ImGui::CalcTextSize("MIS").x + ImGui::GetStyle().ItemSpacing.x);
    ImGui::BeginDisabled(edited.integrator == IntegratorKind::Mlt);
    ImGui::RadioButton("variance-aware", &heuristic, static_cast<int>(MisHeuristic::VarianceAware));
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("balance with each technique's count times its second moment over its variance, estimated\n"
                        "per 8x8 region from the passes so far (Grittmann et al. 2019): balance for the first %d\n"
                        "passes; unbiased, as each pass weighs with the passes before it. Not with mlt.",
                        kVarianceAwarePilotPasses);
    ImGui::SameLine();
    ImGui::BeginDisabled(edited.integrator != IntegratorKind::Bpt);
    ImGui::RadioButton("optimal", &heuristic, static_cast<int>(MisHeuristic::Optimal));
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("the balance weights plus the correction that makes them the weights of least variance\n"
                        "(Kondapaneni et al. 2019): coefficients per pixel and length solved from the passes so far,\n"
                        "balance for the first %d passes; unbiased, as each pass uses the passes before it. A pixel\n"
                        "may go slightly negative early on. bpt only, connections only (no merges, no equiangular).",
                        kOptimalMisPilotPasses);
  }
  edited.mis.heuristic = static_cast<MisHeuristic>(heuristic);
  const bool metropolis = edited.integrator == IntegratorKind::Mlt;
  // Metropolis runs over path reuse, every technique weighed: no naive BPT, isolation or check.
  ImGui::BeginDisabled(metropolis);
  bool naive = edited.connect == ConnectStrategy::Endpoints;
  ImGui::Checkbox("naive BPT: connect endpoints only", &naive);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("each technique (s,t) traces a light subpath of s and a camera subpath of t vertices of its own\n"
                      "and connects their endpoints: same weights and expectation as path reuse, more rays a sample");
  edited.connect = naive ? ConnectStrategy::Endpoints : ConnectStrategy::All;
  ImGui::EndDisabled();
  if (metropolis) edited.connect = ConnectStrategy::All;
  if (edited.mis.heuristic == MisHeuristic::Power) ImGui::SliderFloat("beta", &edited.mis.beta, 0.5f, 8.f, "%.2f");
  ImGui::SliderFloat("min connection", &edited.mis.minConnection, 0.f, 0.3f, "%.4f", ImGuiSliderFlags_Logarithmic);
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("connections shorter than this fraction of the scene's radius are left to the techniques\n"
                      "that sample that edge (1/d^2 near corners); unbiased at any value, 0 turns it off.\n"
                      "Uniform weights gain most; balance and power barely notice.");
  // Efficiency-aware sampling's first knob (core/bpt/light_paths.h): path reuse's bpt only.
  const bool lightPathsApply = edited.integrator == IntegratorKind::Bpt && edited.connect == ConnectStrategy::All &&
                               edited.mis.heuristic != MisHeuristic::VarianceAware &&
                               !covers(enabledTechniques(edited).families(), TechniqueKind::Merge);
  // --light-paths auto (core/bpt/light_path_choice.h): balance heuristic only; the slider then
  // shows the F the renderer chose.
  const bool autoApplies = lightPathsApply && edited.mis.heuristic == MisHeuristic::Balance;
  ImGui::BeginDisabled(!lightPathsApply || edited.lightPathsAuto);
  float shown = edited.lightPathsAuto && lightPaths ? lightPaths->lightPaths : edited.lightPaths;
  ImGui::SliderFloat("light paths", &shown, 0.01f, 1.f, "%.3f", ImGuiSliderFlags_Logarithmic);
  if (!edited.lightPathsAuto) edited.lightPaths = shown;
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("light subpaths per camera sample: each camera sample walks one with this probability.\n"
                      "Light tracing and the connections beyond next-event estimation count it in every MIS\n"
                      "weight and are divided by it: unbiased at any value, cheaper below 1 where they help little.\n"
                      "bpt with path reuse only (not merges, naive BPT or variance-aware MIS).");
  ImGui::BeginDisabled(!autoApplies);
  ImGui::Checkbox("light paths: auto", &edited.lightPathsAuto);
  ImGui::EndDisabled();
  if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("choose the light subpaths per camera sample from the passes themselves (Grittmann et al. 2022):\n"
                      "each candidate's second moment estimated from the samples of the current one, times its\n"
                      "cost in rays; chosen after 4, 8, 16, 32, ... passes. Balance heuristic only.");
  if (!autoApplies) edited.lightPathsAuto = false;
  if (edited.lightPathsAuto) {
    edited.lightPaths = 1.f;  // the pilot passes' F
    if (lightPaths && !lightPaths->estimates.empty()) {
      const auto chosen = std::find_if(lightPaths->estimates.begin(), lightPaths->estimates.end(),
                                       [&](const LightPathEstimate& e) { return e.lightPaths == lightPaths->lightPaths; });
      ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
      ImGui::TextWrapped("F = %.3g chosen from %llu learning passes: est. %.2fx the efficiency of F = 1 (hover: every "
                         "candidate)",
                         lightPaths->lightPaths, static_cast<unsigned long long>(lightPaths->passes),
                         chosen != lightPaths->estimates.end() ? chosen->efficiency : 1.0);
      ImGui::PopStyleColor();
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", lightPathTable(*lightPaths).c_str());
    } else {
      ImGui::TextDisabled("F = 1 until the first choice, after %d passes", kLightPathPilotPasses);
    }
  }
  edited.lightPaths = lightPathsApply ? std::clamp(edited.lightPaths, kMinLightPaths, 1.f) : 1.f;

  // Mode
  int mode = static_cast<int>(estimator.mode);
  ImGui::BeginDisabled(metropolis);
  for (int m = 0; m < 3; ++m) ImGui::RadioButton(modeLabel(static_cast<EstimatorMode>(m)), &mode, m);
  ImGui::EndDisabled();
  estimator.mode = static_cast<EstimatorMode>(mode);
  if (estimator.mode != EstimatorMode::Combine && !metropolis) {
    const Technique x = estimator.isolated;
    ImGui::Text("isolated technique %s%s, length %d", x.kind == TechniqueKind::Connection ? "(s,t) = " : "",
                techniqueLabel(x).c_str(),
                x.length());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("click a cell of the grid or a pyramid thumbnail; arrow keys move it");
    if (isolatedTechniqueDisabled(renderSettings(estimator))) {
      ImGui::PushStyleColor(ImGuiCol_Text, kTechniqueWarning);
      ImGui::TextWrapped("%s is not enabled: its weighted share is zero (Ctrl+click enables it)",
                         techniqueLabel(x).c_str());
      ImGui::PopStyleColor();
    }
  }

  drawMergeControls(edited, radiusNow);

  ImGui::Separator();
  drawTechniqueGrid(estimator, grid, counters, check, sampled);
  ImGui::BeginDisabled(metropolis);
  drawCheckControls(estimator, grid, check);
  ImGui::EndDisabled();
  ImGui::EndDisabled();
  if (!bidirectional) ImGui::TextDisabled("the path tracer ignores the technique set");

  if (!settingsError.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("refused: %s", settingsError.c_str());
    ImGui::PopStyleColor();
  }
  ImGui::PopID();
}

}  // namespace pathlab::ui
