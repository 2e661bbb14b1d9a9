// inspectSample: one camera sample replayed with its trace, its splats on a scratch film;
// inspectChain: a Metropolis chain's state replayed with its trace.
#include "core/render/sample_inspection.h"

#include "core/render/sample_outputs.h"

#include <fmt/core.h>

#include <cmath>
#include <stdexcept>

namespace pathlab {

SampleInspection inspectSample(const RenderSession& session, int x, int y, uint64_t sample) {
  SampleInspection r;
  r.x = x;
  r.y = y;
  r.sample = sample;
  Counters counters;
  Film splats(session.settings().width, session.settings().height);
  r.cameraEstimate = session.replaySample(x, y, sample, counters, &splats, &r.trace);
  if (const OptimalMis* optimal = session.optimalMis(); optimal && optimal->active()) {
    r.optimalBeta.resize(r.trace.records.size());
    r.optimalCorrection.assign(r.trace.records.size(), Spectrum(0.f));
    for (size_t i = 0; i < r.trace.records.size() && i < r.trace.onPath.size(); ++i) {
      const TechniqueResult& t = r.trace.records[i];
      if (t.outcome != TechniqueOutcome::Contributed || t.kind != TechniqueKind::Connection || !t.inImage) continue;
      const Vec2 at = t.t == 1 ? t.pRaster : Vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const int n = t.s + t.t, region = optimal->regionOf(at);
      std::vector<double> w(static_cast<size_t>(n), 0.0);
      for (const TechniqueOnPath& y : r.trace.onPath[i])
        if (y.kind == TechniqueKind::Connection && y.counted && y.s >= 0 && y.s < n) w[static_cast<size_t>(y.s)] = y.balance;
      for (int sp = 0; sp < n; ++sp) r.optimalBeta[i].push_back(optimal->beta(region, sp, n));
      r.optimalCorrection[i] = optimal->correction(region, t.s, n, w.data()) * t.omittedFactor;
    }
  }
  return r;
}

SampleInspection inspectChain(RenderSession& session, uint64_t chain, uint64_t passes, const std::atomic<bool>* cancel) {
  Metropolis* metropolis = session.metropolis();
  if (!metropolis) throw std::invalid_argument("only a Metropolis render (--integrator mlt) has chains to inspect");
  while (session.passes() < passes)
    if (!session.renderPass(cancel)) throw std::runtime_error("the inspection was cancelled");
  if (!metropolis->bootstrapped()) {
    Counters counters;
    if (!metropolis->bootstrap(counters, cancel)) throw std::runtime_error("the inspection was cancelled");
  }
  const size_t count = metropolis->chainCount();
  if (chain >= count)
    throw std::invalid_argument(
        count == 0 ? std::string("this render has no chains: every enabled technique is rendered by BPT (--mlt-direct)")
                   : fmt::format("--chain {} is past the last chain, {}", chain, count - 1));
  SampleInspection r;
  r.sample = session.passes();
  r.chains = static_cast<int>(count);
  SampleTargets targets;
  targets.trace = &r.trace;
  SampleOutputs outputs(targets);
  r.chain = metropolis->replayChain(static_cast<size_t>(chain), &outputs);
  r.x = r.y = -1;
  if (!r.chain->contributions.empty()) {
    const Vec2 p = r.chain->contributions.front().pRaster;
    r.x = static_cast<int>(std::floor(p.x)), r.y = static_cast<int>(std::floor(p.y));
  }
  // The state's estimate of its own pixel: its contributions that land there (MMLT: its one).
  for (const MltChainState::Contribution& c : r.chain->contributions)
    if (static_cast<int>(std::floor(c.pRaster.x)) == r.x && static_cast<int>(std::floor(c.pRaster.y)) == r.y)
      r.cameraEstimate += c.L;
  return r;
}

}  // namespace pathlab
