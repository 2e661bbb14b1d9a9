// One configuration rendered progressively with its error recorded at geometrically spaced
// checkpoints: the measurement behind `pathlab converge` (and, later, the viewer's live plot).
#pragma once

#include "core/converge/checkpoint_exchange.h"
#include "core/converge/convergence_config.h"
#include "core/counters/counters.h"
#include "core/metrics/error_metrics.h"
#include "core/scene/scene.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab {

// Which clock measures render time. Wall: what a user waits. Cpu: the process's CPU time
// (CLOCK_PROCESS_CPUTIME_ID, all threads): on a shared machine whose load exceeds its cores it
// counts only the time the render actually ran, so comparisons stay fair while other processes
// come and go. With several threads it also counts TBB workers spinning for work: use it with
// --threads 1.
enum class ClockKind { Wall, Cpu };

struct Checkpoint {
  double seconds = 0.0;  // render time on the budget's clock: the sum of renderPass durations, metrics excluded
  double wallSeconds = 0.0, cpuSeconds = 0.0;  // both clocks, whichever the budget uses
  uint64_t spp = 0;
  std::optional<ErrorMetrics> error;  // against the reference, when there is one
  std::optional<RelMseSplit> split;   // error->relMse as bias^2 + variance (splitRelMse), with a reference
  TwoBufferEstimate twoBuffer;        // zeros until two passes are done
  uint64_t cameraSamples = 0, rays = 0;  // rays: closest-hit and shadow queries
};

// Either a time or a sample count. Checkpoints follow a geometric sequence in that quantity:
// after the first pass, then whenever it has grown by `factor` since the last checkpoint, and at
// the end, so a log-log plot gets evenly spaced points.
struct ConvergenceBudget {
  double seconds = 0.0;  // > 0: render for this much render time (at least two passes)
  uint64_t spp = 0;      // > 0: render this many passes
  double factor = 1.5;
  ClockKind clock = ClockKind::Wall;
};

// Split over several processes (CheckpointExchange), a checkpoint is the run's: its times are the
// slowest process's, its counts and its image (errors on the leader only) those of all processes.
struct ConvergenceCurve {
  std::string label;
  std::vector<Checkpoint> checkpoints;
  Counters counters;  // this process's
  Image image;        // the final mean (on the leader)
  int processes = 1;  // that rendered it together
};

using CheckpointCallback = std::function<void(const Checkpoint&)>;

// Thrown by runConvergence when its `stop` flag is set: the run ends after the pass in progress.
class ConvergenceStopped : public std::runtime_error {
 public:
  ConvergenceStopped() : std::runtime_error("the convergence run was stopped") {}
};

// Blocking; uses the caller's TBB arena. `reference` may be null (then only the two-buffer
// estimate is recorded). `passesDone`, if given, is updated after each pass (progress display).
// `exchange`: the processes rendering the run together, each calling this (null: this one alone).
// `mask`: the pixels the error against the reference is measured over (empty: all). `stop`, when
// set (from any thread), ends the run after the pass in progress by throwing ConvergenceStopped
// (one process only: the Python module's Ctrl+C).
ConvergenceCurve runConvergence(const Scene& scene, const ConvergenceConfig& config, const Image* reference,
                                const ConvergenceBudget& budget, const CheckpointCallback& onCheckpoint = {},
                                std::atomic<uint64_t>* passesDone = nullptr, CheckpointExchange* exchange = nullptr,
                                const PixelMask& mask = {}, const std::atomic<bool>* stop = nullptr);

}  // namespace pathlab
