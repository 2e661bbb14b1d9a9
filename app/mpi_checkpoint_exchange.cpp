// A checkpoint's collectives over MPI_COMM_WORLD.
#include "app/mpi_checkpoint_exchange.h"

#include "app/mpi_collectives.h"

#include <stdexcept>
#include <type_traits>

namespace pathlab::app {

// Every rank runs the same build of pathlab: the plain struct travels as bytes.
static_assert(std::is_trivially_copyable_v<RunProgress>);

std::vector<RunProgress> MpiCheckpointExchange::gatherProgress(const RunProgress& own) {
  // A rank that reaches the checkpoint first waits for the others asleep: they are still
  // rendering, maybe on the same cores.
  std::vector<RunProgress> all(static_cast<size_t>(size_));
  MPI_Request request;
  MPI_Iallgather(&own, sizeof(RunProgress), MPI_BYTE, all.data(), sizeof(RunProgress), MPI_BYTE, MPI_COMM_WORLD,
                 &request);
  waitAsleep(request);
  return all;
}

void MpiCheckpointExchange::sumToLeader(std::span<const double> own, std::span<double> total) {
  if (leader() && own.size() != total.size()) throw std::invalid_argument("sums of different sizes cannot be added");
  sumToRank0(own.data(), total.data(), own.size(), leader());
}

}  // namespace pathlab::app
