// The converge loop: passes of one RenderSession, per-pass images split into even and odd
// buffers, metrics at geometric checkpoints.
#include "core/converge/convergence.h"

#include "core/render/render_session.h"

#include <chrono>
#include <ctime>
#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

double processCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

ConvergenceCurve runConvergence(const Scene& scene, const ConvergenceConfig& config, const Image* reference,
                                const ConvergenceBudget& budget, const CheckpointCallback& onCheckpoint,
                                std::atomic<uint64_t>* passesDone) {
  if ((budget.seconds > 0.0) == (budget.spp > 0))
    throw std::invalid_argument("a convergence run needs either a time or a sample count");
  if (!(budget.factor > 1.0)) throw std::invalid_argument("the checkpoint factor must exceed 1");
  const RenderSettings& s = config.settings;
  if (reference && (reference->width != s.width || reference->height != s.height))
    throw std::invalid_argument("the reference and the configuration differ in size");

  RenderSession session(scene, s);
  // The even/odd split needs each pass's own image. One session per configuration and per-pass
  // images recovered from consecutive running means (EvenOddBuffers::addRunningMean) cost one
  // read-out per pass and change nothing in the core; two sessions (one for even, one for odd
  // passes) would need the same read-outs and a second film, and would have to be driven with
  // interleaved pass indices to stay the same estimator as one session.
  EvenOddBuffers buffers(s.width, s.height);
  ConvergenceCurve curve{config.label, {}, {}, {}};
  double renderSeconds = 0.0, wallSeconds = 0.0, cpuSeconds = 0.0;
  double lastCheckpoint = 0.0;  // in the budget's quantity
  const bool timed = budget.seconds > 0.0;

  auto record = [&](const Image& mean) {
    Checkpoint c;
    c.seconds = renderSeconds;
    c.wallSeconds = wallSeconds;
    c.cpuSeconds = cpuSeconds;
    c.spp = session.passes();
    if (reference) c.error = errorMetrics(mean, *reference);
    c.twoBuffer = buffers.estimate();
    c.cameraSamples = session.counters().cameraSamples;
    c.rays = session.counters().totalRays();
    curve.checkpoints.push_back(c);
    lastCheckpoint = timed ? renderSeconds : static_cast<double>(c.spp);
    if (onCheckpoint) onCheckpoint(c);
  };

  for (;;) {
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = processCpuSeconds();
    session.renderPass();
    wallSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    cpuSeconds += processCpuSeconds() - cpuStart;
    renderSeconds = budget.clock == ClockKind::Cpu ? cpuSeconds : wallSeconds;
    if (passesDone) passesDone->store(session.passes(), std::memory_order_relaxed);
    const Image mean = session.image();
    buffers.addRunningMean(mean);

    // Two passes at least, so the two-buffer estimate exists at the end.
    const bool done = timed ? (renderSeconds >= budget.seconds && session.passes() >= 2) : session.passes() >= budget.spp;
    const double progress = timed ? renderSeconds : static_cast<double>(session.passes());
    if (done || session.passes() == 1 || progress >= lastCheckpoint * budget.factor) record(mean);
    if (done) {
      curve.image = mean;
      break;
    }
  }
  curve.counters = session.counters();
  return curve;
}

}  // namespace pathlab
