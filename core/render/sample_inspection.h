// One camera sample replayed exactly as the render computed it, every technique it tried recorded
// with its full path (SampleTrace): what `pathlab inspect`, `render --replay` and the viewer's path
// inspector show (issue 12).
#pragma once

#include "core/bpt/technique_result.h"
#include "core/render/render_session.h"

#include <cstdint>

namespace pathlab {

struct SampleInspection {
  int x = 0, y = 0;
  uint64_t sample = 0;
  Spectrum cameraEstimate{0.f};  // the sample's camera-side estimate (its t = 1 splats land elsewhere)
  SampleTrace trace;
};

// Replays sample (pass) `sample` of pixel (x, y) with `session`'s settings.
SampleInspection inspectSample(const RenderSession& session, int x, int y, uint64_t sample);

}  // namespace pathlab
