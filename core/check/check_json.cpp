// checkJson: the check's reports as plain JSON values (relative differences as fractions).
#include "core/check/check_json.h"

#include "core/sampling/technique_label.h"

#include <fmt/format.h>

namespace pathlab {

namespace {

std::string region(int r, int blocks) {
  if (r < 0) return "";
  if (r == TechniqueCheck::wholeImage(blocks)) return "whole image";
  return fmt::format("block ({},{})", r % blocks, r / blocks);
}

nlohmann::json fitJson(const RadiusFit& f, double reference) {
  return {{"difference", f.atZero}, {"standardError", f.standardError},
          {"relative", reference != 0.0 ? f.atZero / reference : 0.0}, {"z", f.z}, {"degree", f.degree}, {"valid", f.valid}};
}

}  // namespace

nlohmann::json checkJson(const CheckReport& report, const MergeBiasReport* merges) {
  nlohmann::json out;
  nlohmann::json connections = nlohmann::json::array();
  for (const TechniqueVerdict& v : report.techniques) {
    nlohmann::json t = {{"technique", techniqueLabel(v.technique)}, {"length", v.technique.length()},
                        {"status", checkStatusName(v.status)},     {"z", v.z},
                        {"wholeImageZ", v.wholeImageZ},            {"pValue", v.pValue},
                        {"worstRegion", region(v.worstRegion, report.blocks)}};
    if (v.worst.valid)
      t["worst"] = {{"partner", techniqueLabel(v.worst.partner)},
                    {"difference", v.worst.difference},
                    {"standardError", v.worst.standardError},
                    {"relative", v.worst.partnerMean != 0.0 ? v.worst.difference / v.worst.partnerMean : 0.0}};
    connections.push_back(t);
  }
  out["techniques"] = connections;
  out["passes"] = report.passes;
  out["blocks"] = report.blocks;
  out["alpha"] = report.options.alpha;
  bool agrees = report.agrees();
  if (merges) {
    nlohmann::json list = nlohmann::json::array();
    for (const MergeVerdict& v : merges->merges) {
      double reference = 0.0;  // the partner's estimate at the largest valid radius, as the text
      for (const RadiusDifference& p : v.wholeImage)
        if (p.valid && reference == 0.0) reference = p.partnerMean;
      nlohmann::json radii = nlohmann::json::array();
      for (const RadiusDifference& p : v.wholeImage)
        radii.push_back({{"radius", p.radius},
                         {"difference", p.difference},
                         {"standardError", p.standardError},
                         {"relative", reference != 0.0 ? p.difference / reference : 0.0},
                         {"valid", p.valid}});
      list.push_back({{"technique", techniqueLabel(v.technique)},
                      {"length", v.technique.length()},
                      {"status", checkStatusName(v.status)},
                      {"partner", v.wholeImage.empty() ? "" : techniqueLabel(v.partner)},
                      {"wholeImage", radii},
                      {"extrapolated", fitJson(v.wholeImageFit, reference)},
                      {"biasShrinking", v.shrinking()},
                      {"z", v.z},
                      {"pValue", v.pValue},
                      {"worstRegion", region(v.worstRegion, merges->blocks)},
                      {"worstPartner", v.worstRegion < 0 ? "" : techniqueLabel(v.worstPartner)}});
    }
    out["merges"] = {{"radii", merges->radii}, {"passesPerRadius", merges->passesPerRadius}, {"techniques", list}};
    agrees = agrees && merges->agrees();
  }
  out["agrees"] = agrees;
  return out;
}

}  // namespace pathlab
