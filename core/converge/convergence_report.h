// What `pathlab converge` writes: the checkpoints as CSV and the efficiency table as Markdown.
#pragma once

#include "core/converge/convergence.h"

#include <string>
#include <vector>

namespace pathlab {

// One row per checkpoint: config, spp, seconds (on the budget's clock), rmse, relmse, mape (empty
// without a reference), twobuffer_mse, twobuffer_relmse, camera_samples, rays, wall_seconds,
// cpu_seconds, relmse_bias2, relmse_variance (relmse split as RelMseSplit: empty without a reference
// or before two passes), and when processes rendered the runs together (ConvergenceCurve::processes),
// ranks: how many. Labels are quoted (RFC 4180): they contain commas.
std::string convergenceCsv(const std::vector<ConvergenceCurve>& curves);

// Efficiency of a Monte Carlo estimator = 1 / (variance × time) (Hammersley and Handscomb 1964;
// Veach 1997, ch. 2), here with relMSE as the error, taken at each configuration's last
// checkpoint; the speed-up over the first configuration says how many times less time it needs
// for the same relMSE (relMSE falls as 1/time for an unbiased estimator). Needs a reference.
struct EfficiencyRow {
  std::string label;
  uint64_t spp = 0;
  double seconds = 0.0, relMse = 0.0, rmse = 0.0, mape = 0.0, twoBufferRelMse = 0.0;
  double efficiency = 0.0, speedup = 0.0;
};
std::vector<EfficiencyRow> efficiencyRows(const std::vector<ConvergenceCurve>& curves);
// `timeHeading` names the clock of the time column ("time (s)", "CPU time (s)").
std::string efficiencyMarkdown(const std::vector<EfficiencyRow>& rows, const std::string& timeHeading = "time (s)");

}  // namespace pathlab
