// The consistency check's verdict as JSON (`pathlab check --json`): the connections' pairwise
// comparisons and, with merging techniques, each merge's difference radius by radius and
// extrapolated to r -> 0 (merge_bias.h), for a lecture's plot of the bias against the radius.
#pragma once

#include "core/check/check_report.h"
#include "core/check/merge_bias.h"

#include <nlohmann/json.hpp>

namespace pathlab {

// `merges` may be null (no merging technique enabled).
nlohmann::json checkJson(const CheckReport& connections, const MergeBiasReport* merges);

}  // namespace pathlab
