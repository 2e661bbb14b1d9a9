// The run of one process: its own progress and sums are the run's.
#include "core/converge/checkpoint_exchange.h"

#include <algorithm>
#include <stdexcept>

namespace pathlab {

RunProgress combineProgress(std::span<const RunProgress> processes) {
  RunProgress run;
  for (const RunProgress& p : processes) {
    run.renderSeconds = std::max(run.renderSeconds, p.renderSeconds);
    run.wallSeconds = std::max(run.wallSeconds, p.wallSeconds);
    run.cpuSeconds = std::max(run.cpuSeconds, p.cpuSeconds);
    run.passes += p.passes;
    run.lightSubpaths += p.lightSubpaths;
    run.cameraSamples += p.cameraSamples;
    run.rays += p.rays;
    run.evenPasses += p.evenPasses;
    run.oddPasses += p.oddPasses;
  }
  return run;
}

void CheckpointExchange::sumToLeader(std::span<const double> own, std::span<double> total) {
  if (own.size() != total.size()) throw std::invalid_argument("sums of different sizes cannot be added");
  std::copy(own.begin(), own.end(), total.begin());
}

}  // namespace pathlab
