// One camera sample replayed exactly as the render computed it, every technique it tried recorded
// with its full path (SampleTrace): what `pathlab inspect`, `render --replay` and the viewer's path
// inspector show (issue 12).
#pragma once

#include "core/bpt/technique_result.h"
#include "core/render/render_session.h"

#include <atomic>
#include <cstdint>
#include <optional>

namespace pathlab {

struct SampleInspection {
  int x = 0, y = 0;
  uint64_t sample = 0;
  Spectrum cameraEstimate{0.f};  // the sample's camera-side estimate (its t = 1 splats land elsewhere)
  SampleTrace trace;
  // A Metropolis render's sample (inspectChain): the chain's state, its primary numbers and
  // contributions; (x, y) is the pixel its first contribution lands in (-1, -1: it has none) and
  // `sample` the passes the chain had run.
  std::optional<MltChainState> chain;
  int chains = 0;  // the render's chain count
  // --mis optimal (core/bpt/optimal_mis.h), when the session has rendered the passes before the
  // sample: per record, the coefficients beta of its length's techniques at its pixel by slot s'
  // (empty for a record that did not contribute) and the correction beta_s - sum beta_k w_k its
  // contribution received (w the path's balance weights, its trace's onPath).
  std::vector<std::vector<Spectrum>> optimalBeta;
  std::vector<Spectrum> optimalCorrection;
};

// Replays sample (pass) `sample` of pixel (x, y) with `session`'s settings.
SampleInspection inspectSample(const RenderSession& session, int x, int y, uint64_t sample);

// A Metropolis render's sample: chain `chain`'s state after `passes` of `session`'s passes (0:
// the state it starts from, resampled from the bootstrap), replayed from its primary numbers with
// its trace. Renders the passes the session has not (the same seed gives the same chains).
// Throws std::invalid_argument when the render has no chain `chain`, std::runtime_error when a
// pass was cancelled.
SampleInspection inspectChain(RenderSession& session, uint64_t chain, uint64_t passes,
                              const std::atomic<bool>* cancel = nullptr);

}  // namespace pathlab
