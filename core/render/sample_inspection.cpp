// inspectSample: one camera sample replayed with its trace, its splats on a scratch film.
#include "core/render/sample_inspection.h"

namespace pathlab {

SampleInspection inspectSample(const RenderSession& session, int x, int y, uint64_t sample) {
  SampleInspection r;
  r.x = x;
  r.y = y;
  r.sample = sample;
  Counters counters;
  Film splats(session.settings().width, session.settings().height);
  r.cameraEstimate = session.replaySample(x, y, sample, counters, &splats, &r.trace);
  return r;
}

}  // namespace pathlab
