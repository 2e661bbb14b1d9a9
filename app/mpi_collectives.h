// MPI steps the render and converge commands share: waiting for a collective without taking a
// core from the ranks still rendering, and adding films into rank 0 in pieces.
// Built only with MPI (PATHLAB_HAVE_MPI).
#pragma once

#include <mpi.h>

#include <cstddef>

namespace pathlab::app {

// Returns when `request` completes, asleep meanwhile: Open MPI's blocking collectives poll, and on
// a machine shared by several ranks that polling would take cores from those still rendering.
void waitAsleep(MPI_Request& request);

// Collective over MPI_COMM_WORLD: every rank's `count` doubles at `own` added into `total` on rank
// 0 (`total` == `own` there: in place; ignored on the other ranks).
void sumToRank0(const double* own, double* total, size_t count, bool leader);

// Collective over MPI_COMM_WORLD: every rank's `count` doubles at `values` summed in place on
// every rank (asleep while waiting for the others).
void sumEverywhere(double* values, size_t count);

}  // namespace pathlab::app
