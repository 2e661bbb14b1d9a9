// How the processes that render one convergence run together (the ranks of an MPI job) meet at its
// checkpoints. This base class is the run of one process, where every exchange is the identity;
// app/ implements it over MPI, so core/ knows nothing of MPI.
#pragma once

#include "core/render/render_session.h"

#include <cstdint>
#include <span>
#include <vector>

namespace pathlab {

// One process's progress at a checkpoint, or the run's once combined (combineProgress).
struct RunProgress {
  // Render times on each clock (passes only): the run's is the slowest process's.
  double renderSeconds = 0.0, wallSeconds = 0.0, cpuSeconds = 0.0;
  // Counts: the run's is the sum over processes.
  uint64_t passes = 0, lightSubpaths = 0, cameraSamples = 0, rays = 0, evenPasses = 0, oddPasses = 0;
};
// The run's progress from every process's (the slowest time, the summed counts).
RunProgress combineProgress(std::span<const RunProgress> processes);

class CheckpointExchange {
 public:
  virtual ~CheckpointExchange() = default;

  virtual int processes() const { return 1; }
  // The process that computes the error and keeps the run's image.
  virtual bool leader() const { return true; }
  // Which pass indices this process renders: interleaved, so that the processes together render
  // the samples one process would (PassSchedule).
  virtual PassSchedule passSchedule() const { return {}; }

  // Collective, once per checkpoint on every process: every process's progress, the same list on
  // each, so each decides alike whether the run is done and when the next checkpoint is.
  virtual std::vector<RunProgress> gatherProgress(const RunProgress& own) { return {own}; }
  // Collective, right after gatherProgress: `own` added element by element into `total` on the
  // leader (of the same size; on the other processes `total` is not written).
  virtual void sumToLeader(std::span<const double> own, std::span<double> total);
};

}  // namespace pathlab
