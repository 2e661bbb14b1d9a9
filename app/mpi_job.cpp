// Job over MPI: the readiness vote after loading, the leader's progress messages, the reduction
// of every rank's film sums, pass counts and counters into the leader's session, and the leader's
// decisions shared.
#include "app/mpi_job.h"

#include "app/mpi_checkpoint_exchange.h"
#include "app/mpi_collectives.h"

#include <fmt/core.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <type_traits>

namespace pathlab::app {

namespace {

constexpr int kProgressTag = 1;  // a rank's pass count so far
constexpr int kDoneTag = 2;      // its last pass count: it has stopped rendering
// Non-leaders tell the leader their progress at most this often (the leader's bar redraws every
// 200 ms); their last count always.
constexpr auto kProgressInterval = std::chrono::milliseconds(200);
constexpr size_t kLineLength = 400;

// What each rank tells the leader when it is done. Counters is plain data (counters.h) and every
// rank runs the same build of pathlab, so it travels as bytes.
struct RankTotals {
  uint64_t passes = 0;
  double seconds = 0.0;
  Counters counters;
};
static_assert(std::is_trivially_copyable_v<RankTotals>);

// Set in the environment of the processes a launcher starts: Open MPI's mpirun, and the PMI and
// PMIx interfaces through which schedulers (Slurm's srun) start MPI programs.
bool launchedByMpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(name)) return true;
  return false;
}

}  // namespace

std::unique_ptr<MpiJob> MpiJob::startIfLaunched(int* argc, char*** argv) {
  if (!launchedByMpi()) return nullptr;
  // Only the main thread calls MPI (the render threads never do).
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return std::unique_ptr<MpiJob>(new MpiJob(rank, size));
}

MpiJob::MpiJob(int rank, int size) : rank_(rank), size_(size), passesOfRank_(static_cast<size_t>(size), 0) {
  MPI_Comm_dup(MPI_COMM_WORLD, &progressComm_);
}

MpiJob::~MpiJob() {
  MPI_Comm_free(&progressComm_);
  MPI_Finalize();
}

void MpiJob::abort(int code) { MPI_Abort(MPI_COMM_WORLD, code); }

void MpiJob::shareLeaders(std::span<uint64_t> values) {
  MPI_Bcast(values.data(), static_cast<int>(values.size()), MPI_UINT64_T, 0, MPI_COMM_WORLD);
}

void MpiJob::sumEverywhere(std::span<double> values) {
  if (size_ > 1) app::sumEverywhere(values.data(), values.size());
}

std::unique_ptr<CheckpointExchange> MpiJob::checkpointExchange() {
  if (size_ == 1) return Job::checkpointExchange();  // `mpirun -n 1`: exactly as one process
  return std::make_unique<MpiCheckpointExchange>(rank_, size_);
}

void MpiJob::agree(const std::string& error, uint64_t shape) {
  if (size_ == 1) return Job::agree(error, shape);  // `mpirun -n 1`: exactly as one process
  // One allreduce decides: anyone failed, or two shapes differ (max(shape) != min(shape)). Halved
  // so that its negation fits an int64.
  const int64_t half = static_cast<int64_t>(shape >> 1);
  int64_t vote[3] = {error.empty() ? 0 : 1, half, -half};
  MPI_Allreduce(MPI_IN_PLACE, vote, 3, MPI_INT64_T, MPI_MAX, MPI_COMM_WORLD);
  if (vote[0] == 0 && vote[1] == -vote[2]) return;

  // Someone is not ready: the leader learns who and why, every rank stops.
  struct Report {
    char line[kLineLength];
    uint64_t shape;
  };
  Report mine{};
  std::strncpy(mine.line, error.c_str(), kLineLength - 1);
  mine.shape = shape;
  std::vector<Report> all(leader() ? static_cast<size_t>(size_) : 0);
  MPI_Gather(&mine, sizeof(Report), MPI_BYTE, all.data(), sizeof(Report), MPI_BYTE, 0, MPI_COMM_WORLD);
  if (!leader()) throw JobStopped("");
  int firstFailed = -1, failed = 0;
  for (int r = 0; r < size_; ++r)
    if (all[static_cast<size_t>(r)].line[0] != '\0') {
      if (firstFailed < 0) firstFailed = r;
      ++failed;
    }
  if (firstFailed >= 0)
    throw JobStopped(fmt::format("rank {} of {}: {}{}", firstFailed, size_, all[static_cast<size_t>(firstFailed)].line,
                                 failed > 1 ? fmt::format(" (and {} more rank{})", failed - 1, failed > 2 ? "s" : "") : ""));
  for (int r = 1; r < size_; ++r)
    if (all[static_cast<size_t>(r)].shape != all[0].shape)
      throw JobStopped(fmt::format("rank {} of {}: its image differs in size from rank 0's (is the scene the same file "
                                   "on every node?)",
                                   r, size_));
  throw JobStopped("the ranks disagree on the image size");
}

void MpiJob::notePasses(uint64_t passes) {
  ownPasses_ = passes;
  if (leader()) {
    passesOfRank_[0] = passes;
    receiveProgress(false);
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (now - lastSent_ < kProgressInterval) return;
  lastSent_ = now;
  // Eight bytes go out eagerly: this does not wait for the leader.
  MPI_Send(&ownPasses_, 1, MPI_UINT64_T, 0, kProgressTag, progressComm_);
}

void MpiJob::receiveProgress(bool untilAllDone) {
  for (;;) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, progressComm_, &arrived, &status);
    if (arrived) {
      uint64_t passes = 0;
      MPI_Recv(&passes, 1, MPI_UINT64_T, status.MPI_SOURCE, status.MPI_TAG, progressComm_, MPI_STATUS_IGNORE);
      passesOfRank_[static_cast<size_t>(status.MPI_SOURCE)] = passes;
      if (status.MPI_TAG == kDoneTag) ++ranksDone_;
    }
    uint64_t known = 0;
    for (uint64_t p : passesOfRank_) known += p;
    knownPasses_.store(known, std::memory_order_relaxed);
    if (arrived) continue;
    if (!untilAllDone || ranksDone_ == size_ - 1) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

JobTotals MpiJob::combine(RenderSession& session, double seconds) {
  ownPasses_ = session.passes();
  // The leader's progress bar follows the others to their last pass (every message is taken, so
  // none is left unreceived at MPI_Finalize).
  if (leader()) {
    passesOfRank_[0] = ownPasses_;
    receiveProgress(true);
  } else {
    MPI_Send(&ownPasses_, 1, MPI_UINT64_T, 0, kDoneTag, progressComm_);
  }
  // A rank done early waits for the slowest asleep (waitAsleep).
  MPI_Request everyoneDone;
  MPI_Ibarrier(MPI_COMM_WORLD, &everyoneDone);
  waitAsleep(everyoneDone);

  RankTotals mine{ownPasses_, seconds, session.counters()};
  std::vector<RankTotals> all(leader() ? static_cast<size_t>(size_) : 0);
  MPI_Gather(&mine, sizeof(RankTotals), MPI_BYTE, all.data(), sizeof(RankTotals), MPI_BYTE, 0, MPI_COMM_WORLD);

  const auto reduceStart = std::chrono::steady_clock::now();
  // Every sum added element by element into the leader's (agree checked the shapes match). The
  // order of the additions differs from one process's (pass by pass), by rounding only.
  for (std::span<double> sum : session.sums()) sumToRank0(sum.data(), sum.data(), sum.size(), leader());

  JobTotals totals{ownPasses_, seconds,
                   std::chrono::duration<double>(std::chrono::steady_clock::now() - reduceStart).count()};
  if (!leader()) return totals;
  uint64_t foreignPasses = 0;
  Counters foreign;
  for (size_t r = 1; r < all.size(); ++r) {
    foreignPasses += all[r].passes;
    foreign += all[r].counters;
    totals.slowestSeconds = std::max(totals.slowestSeconds, all[r].seconds);
  }
  session.addForeignPasses(foreignPasses, foreign);
  totals.passes += foreignPasses;
  return totals;
}

}  // namespace pathlab::app
