// The checkpoints of `mpirun -n N pathlab converge`: the ranks meet at each one (their progress
// gathered on every rank, their film and even/odd sums added into rank 0's).
// Built only with MPI (PATHLAB_HAVE_MPI).
#pragma once

#include "core/converge/checkpoint_exchange.h"

namespace pathlab::app {

class MpiCheckpointExchange : public CheckpointExchange {
 public:
  MpiCheckpointExchange(int rank, int size) : rank_(rank), size_(size) {}

  int processes() const override { return size_; }
  bool leader() const override { return rank_ == 0; }
  PassSchedule passSchedule() const override {
    return PassSchedule{static_cast<uint64_t>(rank_), static_cast<uint64_t>(size_)};
  }
  std::vector<RunProgress> gatherProgress(const RunProgress& own) override;
  void sumToLeader(std::span<const double> own, std::span<double> total) override;

 private:
  int rank_, size_;
};

}  // namespace pathlab::app
