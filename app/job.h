// The processes a command runs on: this one alone (the base class, what pathlab does without
// MPI), or the ranks of an MPI job (app/mpi_job.h). The render and converge commands are written
// once against this interface; with one process every call is a no-op or the identity.
#pragma once

#include "core/converge/checkpoint_exchange.h"
#include "core/counters/counters.h"
#include "core/render/render_session.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <ostream>
#include <span>
#include <stdexcept>
#include <string>

namespace pathlab::app {

// The job stops on every rank: `what()` is the line the leader prints (empty on the other ranks,
// which print nothing). main turns it into exit code 1 without MPI_Abort.
class JobStopped : public std::runtime_error {
 public:
  explicit JobStopped(const std::string& line) : std::runtime_error(line) {}
};

// What the leader reports once the ranks' passes are combined.
struct JobTotals {
  uint64_t passes = 0;         // over all ranks
  double slowestSeconds = 0;   // the longest rendering time of any rank
  double reduceSeconds = 0;    // the leader's time adding the ranks' sums (after the slowest rank is done)
};

class Job {
 public:
  virtual ~Job() = default;

  virtual int rank() const { return 0; }
  virtual int size() const { return 1; }
  // Rank 0: the one rank that prints, asks and writes outputs.
  bool leader() const { return rank() == 0; }
  // std::cerr on the leader, a stream that discards everything on the other ranks.
  std::ostream& log() const;
  // The passes this rank renders of a render of all passes: rank r of N renders r, r + N, ...
  PassSchedule passSchedule() const {
    return PassSchedule{static_cast<uint64_t>(rank()), static_cast<uint64_t>(size())};
  }
  // How many of the first `totalPasses` pass indices this rank's schedule holds.
  uint64_t passesOf(uint64_t totalPasses) const { return passSchedule().passesBelow(totalPasses); }

  // Collective, the first of a command: each rank says whether it is ready (`error` empty) and
  // the shape of what it will accumulate (RenderSession::sums' sizes, shapeOf). Returns when every
  // rank is ready with the same shape; throws JobStopped on every rank otherwise, the leader's line
  // naming the first failing rank and its problem. Without MPI: throws the error, if any.
  virtual void agree(const std::string& error, uint64_t shape);

  // Between passes, on every rank: this rank has rendered `passes` passes so far. The leader
  // learns the others' counts (jobPasses) without waiting for them.
  virtual void notePasses(uint64_t passes) { knownPasses_.store(passes, std::memory_order_relaxed); }
  // Passes of every rank the leader knows of (its own as of its last notePasses); read by the
  // progress bar's thread.
  uint64_t jobPasses() const { return knownPasses_.load(std::memory_order_relaxed); }

  // Collective, after the last pass: every rank's sums, passes and counters added into the
  // leader's session (the other ranks' sessions are left as they were). `seconds` is this rank's
  // rendering time.
  virtual JobTotals combine(RenderSession& session, double seconds);

  // Ends every rank at once, for an error on one rank where the others may be waiting in a
  // collective (outside agree). Without MPI it does nothing: the caller returns its exit code.
  virtual void abort(int code) {}

  // Collective: every rank gets the leader's `values`, for what the leader alone decides (the
  // image size of a reference it read, whether it holds a cached one).
  virtual void shareLeaders(std::span<uint64_t> values) {}
  // Collective: every rank's `values` summed in place on every rank (a Metropolis render's
  // bootstrap weights, Metropolis::setBootstrapExchange). One process: nothing to add.
  virtual void sumEverywhere(std::span<double> values) {}
  // How this job's ranks meet at the checkpoints of a convergence run (converge): one process
  // alone, or the ranks together.
  virtual std::unique_ptr<CheckpointExchange> checkpointExchange() { return std::make_unique<CheckpointExchange>(); }

 protected:
  std::atomic<uint64_t> knownPasses_{0};
};

// A value that differs (almost surely) when two sessions' sums differ in number or size.
uint64_t shapeOf(RenderSession& session);

// Every rank runs `prepare` (options, outputs, scene, session), then all agree before the first
// collective: a rank that could not load the scene stops the job at once, naming itself, instead
// of leaving the others waiting for it in a reduction. `shape(prepared)` is Job::agree's shape.
template <class Prepared, class Prepare, class Shape>
Prepared prepareOnEveryRank(Job& job, Prepare prepare, Shape shape) {
  Prepared prepared;
  std::string error;
  try {
    prepared = prepare();
  } catch (const std::exception& e) {
    error = e.what();
  }
  job.agree(error, shape(prepared));
  return prepared;
}

}  // namespace pathlab::app
