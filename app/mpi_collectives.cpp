// Sleeping waits and reductions in pieces (see the header).
#include "app/mpi_collectives.h"

#include <algorithm>
#include <chrono>
#include <thread>

namespace pathlab::app {

namespace {

// MPI counts are int: large films are reduced in pieces.
constexpr size_t kReduceChunk = size_t{1} << 26;

}  // namespace

void waitAsleep(MPI_Request& request) {
  for (int done = 0;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

void sumToRank0(const double* own, double* total, size_t count, bool leader) {
  for (size_t begin = 0; begin < count; begin += kReduceChunk) {
    const int n = static_cast<int>(std::min(kReduceChunk, count - begin));
    if (!leader) MPI_Reduce(own + begin, nullptr, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    else if (own == total) MPI_Reduce(MPI_IN_PLACE, total + begin, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    else MPI_Reduce(own + begin, total + begin, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  }
}

void sumEverywhere(double* values, size_t count) {
  for (size_t begin = 0; begin < count; begin += kReduceChunk) {
    const int n = static_cast<int>(std::min(kReduceChunk, count - begin));
    MPI_Request request;
    MPI_Iallreduce(MPI_IN_PLACE, values + begin, n, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD, &request);
    waitAsleep(request);
  }
}

}  // namespace pathlab::app
