// One rank of an MPI job (`mpirun -n N pathlab render|converge ...`, or a scheduler's `srun`):
// Job's collectives over MPI_COMM_WORLD, and the leader's view of the other ranks' progress.
// Built only with MPI (PATHLAB_HAVE_MPI).
#pragma once

#include "app/job.h"

#include <mpi.h>

#include <chrono>
#include <memory>
#include <vector>

namespace pathlab::app {

class MpiJob : public Job {
 public:
  // MPI started, when a launcher started this process (Open MPI's, PMI or PMIx environment);
  // null otherwise: pathlab started by hand stays a plain process, exactly as without MPI.
  static std::unique_ptr<MpiJob> startIfLaunched(int* argc, char*** argv);
  ~MpiJob() override;  // MPI_Finalize
  MpiJob(const MpiJob&) = delete;
  MpiJob& operator=(const MpiJob&) = delete;

  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void agree(const std::string& error, uint64_t shape) override;
  void notePasses(uint64_t passes) override;
  JobTotals combine(RenderSession& session, double seconds) override;
  void abort(int code) override;
  void shareLeaders(std::span<uint64_t> values) override;
  void sumEverywhere(std::span<double> values) override;
  std::unique_ptr<CheckpointExchange> checkpointExchange() override;

 private:
  MpiJob(int rank, int size);
  // The leader: takes the progress messages that arrived; with `untilAllDone`, waits until every
  // other rank has sent its last one.
  void receiveProgress(bool untilAllDone);

  int rank_, size_;
  // Progress messages travel on a communicator of their own, apart from any collective.
  MPI_Comm progressComm_ = MPI_COMM_NULL;
  uint64_t ownPasses_ = 0;
  std::vector<uint64_t> passesOfRank_;  // the leader's latest news of every rank
  int ranksDone_ = 0;
  std::chrono::steady_clock::time_point lastSent_{};
};

}  // namespace pathlab::app
