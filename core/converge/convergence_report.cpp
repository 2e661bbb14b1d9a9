// CSV and Markdown output of convergence runs.
#include "core/converge/convergence_report.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

std::string csvQuote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + "\"";
}

// '|' would end a Markdown table cell.
std::string markdownCell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|') out += '\\';
    out += c;
  }
  return "`" + out + "`";
}

}  // namespace

std::string convergenceCsv(const std::vector<ConvergenceCurve>& curves) {
  const bool split = std::any_of(curves.begin(), curves.end(), [](const ConvergenceCurve& c) { return c.processes > 1; });
  std::string csv = "config,spp,seconds,rmse,relmse,mape,twobuffer_mse,twobuffer_relmse,camera_samples,rays,wall_seconds,"
                    "cpu_seconds,relmse_bias2,relmse_variance";
  csv += split ? ",ranks\n" : "\n";
  for (const ConvergenceCurve& curve : curves)
    for (const Checkpoint& c : curve.checkpoints) {
      const std::string errors =
          c.error ? fmt::format("{:.6g},{:.6g},{:.6g}", c.error->rmse, c.error->relMse, c.error->mape) : ",,";
      // Empty where the passes are not independent (Metropolis: NaN).
      const std::string twoBuffer =
          std::isfinite(c.twoBuffer.relMse) ? fmt::format("{:.6g},{:.6g}", c.twoBuffer.mse, c.twoBuffer.relMse) : ",";
      csv += fmt::format("{},{},{:.6f},{},{},{},{},{:.6f},{:.6f}", csvQuote(curve.label), c.spp, c.seconds, errors,
                         twoBuffer, c.cameraSamples, c.rays, c.wallSeconds, c.cpuSeconds);
      csv += c.split ? fmt::format(",{:.6g},{:.6g}", c.split->bias2, c.split->variance) : ",,";
      csv += split ? fmt::format(",{}\n", curve.processes) : "\n";
    }
  return csv;
}

std::vector<EfficiencyRow> efficiencyRows(const std::vector<ConvergenceCurve>& curves) {
  std::vector<EfficiencyRow> rows;
  for (const ConvergenceCurve& curve : curves) {
    if (curve.checkpoints.empty() || !curve.checkpoints.back().error)
      throw std::invalid_argument("the efficiency table needs a reference and at least one checkpoint");
    const Checkpoint& c = curve.checkpoints.back();
    EfficiencyRow r;
    r.label = curve.label;
    r.spp = c.spp;
    r.seconds = c.seconds;
    r.relMse = c.error->relMse;
    r.rmse = c.error->rmse;
    r.mape = c.error->mape;
    r.twoBufferRelMse = c.twoBuffer.relMse;
    r.efficiency = r.relMse > 0.0 && r.seconds > 0.0 ? 1.0 / (r.relMse * r.seconds) : 0.0;
    rows.push_back(r);
  }
  if (!rows.empty())
    for (EfficiencyRow& r : rows) r.speedup = rows.front().efficiency > 0.0 ? r.efficiency / rows.front().efficiency : 0.0;
  return rows;
}

std::string efficiencyMarkdown(const std::vector<EfficiencyRow>& rows, const std::string& timeHeading) {
  std::string md = "| configuration | spp | " + timeHeading +
                   " | relMSE | two-buffer relMSE | RMSE | MAPE | efficiency 1/(relMSE·s) | speed-up |\n"
                   "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const EfficiencyRow& r : rows)
    md += fmt::format("| {} | {} | {:.3g} | {:.4g} | {} | {:.4g} | {:.4g} | {:.4g} | {:.2f}× |\n",
                      markdownCell(r.label), r.spp, r.seconds, r.relMse,
                      std::isfinite(r.twoBufferRelMse) ? fmt::format("{:.4g}", r.twoBufferRelMse) : "–", r.rmse,
                      r.mape, r.efficiency, r.speedup);
  return md;
}

}  // namespace pathlab
