// The converge loop: passes of one RenderSession, per-pass images split into even and odd
// buffers, metrics at geometric checkpoints (the run's, when processes render it together).
#include "core/converge/convergence.h"

#include "core/render/render_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

namespace pathlab {

namespace {

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Adds every process's sums into `total` on the leader (there, of the same sizes as `own`).
template <size_t N>
void sumToLeader(CheckpointExchange& run, const std::array<std::span<const double>, N>& own,
                 const std::array<std::span<double>, N>& total) {
  for (size_t i = 0; i < N; ++i) run.sumToLeader(own[i], run.leader() ? total[i] : std::span<double>());
}

struct RunImage {
  Image mean;
  TwoBufferEstimate twoBuffer;
  std::optional<RelMseSplit> split;  // with a reference and two passes
};

// The split needs the even and odd buffers the mean came from: taken where they are.
std::optional<RelMseSplit> splitAgainst(const EvenOddBuffers& buffers, const Image& mean, const Image* reference,
                                        const PixelMask& mask) {
  if (!reference || buffers.evenPasses() == 0 || buffers.oddPasses() == 0) return std::nullopt;
  return splitRelMse(buffers, mean, *reference, mask);
}

// Collective: the run's mean image and two-buffer estimate on the leader, from every process's
// film and even/odd sums added there; nothing on the other processes. One process's own are the
// run's: read without copies.
std::optional<RunImage> runImageOnLeader(CheckpointExchange& run, const RenderSession& session,
                                         const EvenOddBuffers& buffers, const RunProgress& progress,
                                         const Image* reference, const PixelMask& mask) {
  if (run.processes() == 1) {
    RunImage image{session.image(), buffers.estimate(), {}};
    image.split = splitAgainst(buffers, image.mean, reference, mask);
    return image;
  }
  const int width = session.film().width(), height = session.film().height();
  std::optional<Film> film;
  std::optional<EvenOddBuffers> runBuffers;
  if (run.leader()) {
    film.emplace(width, height);
    runBuffers.emplace(width, height);
  }
  sumToLeader(run, session.film().sums(), film ? film->sums() : std::array<std::span<double>, 2>{});
  sumToLeader(run, buffers.sums(), runBuffers ? runBuffers->sums() : std::array<std::span<double>, 2>{});
  if (!run.leader()) return std::nullopt;
  film->finishPass(progress.passes, progress.lightSubpaths);
  runBuffers->addForeignPasses(progress.evenPasses, progress.oddPasses);
  RunImage image{film->readout(), runBuffers->estimate(), {}};
  image.split = splitAgainst(*runBuffers, image.mean, reference, mask);
  return image;
}

}  // namespace

ConvergenceCurve runConvergence(const Scene& scene, const ConvergenceConfig& config, const Image* reference,
                                const ConvergenceBudget& budget, const CheckpointCallback& onCheckpoint,
                                std::atomic<uint64_t>* passesDone, CheckpointExchange* exchange, const PixelMask& mask,
                                const std::atomic<bool>* stop) {
  if ((budget.seconds > 0.0) == (budget.spp > 0))
    throw std::invalid_argument("a convergence run needs either a time or a sample count");
  if (!(budget.factor > 1.0)) throw std::invalid_argument("the checkpoint factor must exceed 1");
  const RenderSettings& s = config.settings;
  if (reference && (reference->width != s.width || reference->height != s.height))
    throw std::invalid_argument("the reference and the configuration differ in size");
  CheckpointExchange oneProcess;
  CheckpointExchange& run = exchange ? *exchange : oneProcess;
  const PassSchedule schedule = run.passSchedule();

  RenderSession session(scene, s, schedule);
  // The even/odd split needs each pass's own image. One session per configuration and per-pass
  // images recovered from consecutive running means (EvenOddBuffers::addRunningMean) cost one
  // read-out per pass and change nothing in the core; two sessions (one for even, one for odd
  // passes) would need the same read-outs and a second film, and would have to be driven with
  // interleaved pass indices to stay the same estimator as one session.
  EvenOddBuffers buffers(s.width, s.height);
  // Metropolis's passes continue the same chains: its even and odd images are correlated, so the
  // two-buffer estimate and the bias^2 / variance split (which assume independent passes) would
  // understate its error many times (1e-5 against 3e-4 on the door scene): left out, NaN.
  const bool independentPasses = s.integrator != IntegratorKind::Mlt;
  ConvergenceCurve curve{config.label, {}, {}, {}, run.processes()};
  double wallSeconds = 0.0, cpuSeconds = 0.0;
  auto renderSeconds = [&] { return budget.clock == ClockKind::Cpu ? cpuSeconds : wallSeconds; };
  const bool timed = budget.seconds > 0.0;
  // The next checkpoint in the budget's quantity: the first after one pass (of every process).
  double nextSeconds = 0.0;
  uint64_t nextSpp = 1;

  auto renderPass = [&] {
    const uint64_t passIndex = schedule.pass(session.passes());
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuSeconds();
    session.renderPass();
    wallSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpuSeconds += processCpuSeconds() - cpuStart;
    if (passesDone) passesDone->store(session.passes(), std::memory_order_relaxed);
    buffers.addRunningMean(session.image(), passIndex);
    if (stop && stop->load(std::memory_order_relaxed)) throw ConvergenceStopped();
  };

  for (;;) {
    // This process's passes up to the checkpoint. A time: until its own render time reaches it, so
    // that every process meets the others there having rendered as long. Samples: its share of
    // the first nextSpp pass indices, so that the run's checkpoints hold the samples of one process.
    if (timed) {
      do renderPass();
      while (renderSeconds() < nextSeconds);
    } else {
      while (session.passes() < schedule.passesBelow(nextSpp)) renderPass();
    }

    const RunProgress own{renderSeconds(), wallSeconds, cpuSeconds, session.passes(), session.film().lightSubpaths(),
                          session.counters().cameraSamples, session.counters().totalRays(), buffers.evenPasses(),
                          buffers.oddPasses()};
    const RunProgress progress = combineProgress(run.gatherProgress(own));
    Checkpoint c;
    if (!independentPasses) c.twoBuffer.mse = c.twoBuffer.relMse = std::numeric_limits<double>::quiet_NaN();
    c.seconds = progress.renderSeconds;
    c.wallSeconds = progress.wallSeconds;
    c.cpuSeconds = progress.cpuSeconds;
    c.spp = progress.passes;
    c.cameraSamples = progress.cameraSamples;
    c.rays = progress.rays;
    Image mean;
    if (std::optional<RunImage> image = runImageOnLeader(run, session, buffers, progress, reference, mask)) {
      mean = std::move(image->mean);
      if (reference) c.error = errorMetrics(mean, *reference, mask);
      if (independentPasses) {
        c.twoBuffer = image->twoBuffer;
        c.split = image->split;
      }
    }
    curve.checkpoints.push_back(c);
    if (onCheckpoint) onCheckpoint(c);

    // Decided from the run's progress alone, so every process takes the same number of checkpoints.
    // Two passes at least, so the two-buffer estimate exists at the end.
    const bool done = timed ? (progress.renderSeconds >= budget.seconds && progress.passes >= 2)
                            : progress.passes >= budget.spp;
    if (done) {
      curve.image = std::move(mean);
      break;
    }
    // Geometric in the budget's quantity: the first sample count or time `factor` times the last.
    if (timed) nextSeconds = std::min(progress.renderSeconds * budget.factor, budget.seconds);
    else nextSpp = std::min(static_cast<uint64_t>(std::ceil(static_cast<double>(progress.passes) * budget.factor)), budget.spp);
  }
  curve.counters = session.counters();
  return curve;
}

}  // namespace pathlab
