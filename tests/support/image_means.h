// Image means with measured standard errors, the two ways the render tests need them.
#pragma once

#include "core/render/render_session.h"
#include "tests/support/statistics.h"

namespace pathlab::test {

// Per-pass means of channel `channel` (0 = r) of the image, film splats included: pass n adds
// n m_n - (n - 1) m_(n-1) to the running sums (both film terms scale as 1/n). Expects (gtest)
// that no sample was discarded.
MeanEstimate passMeans(const Scene& scene, const RenderSettings& settings, int passes, int channel = 0);

// Whole-image means (every channel) of `seeds` independent renders of `passes` passes each,
// seeds firstSeed, firstSeed + 1, ...: each render one sample. Expects no discarded sample.
MeanEstimate seedMeans(const Scene& scene, RenderSettings settings, int seeds, int passes, uint64_t firstSeed);

}  // namespace pathlab::test
