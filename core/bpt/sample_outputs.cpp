// SampleOutputs: a technique's result into the counters, the trace, the pyramid and the image.
#include "core/bpt/sample_outputs.h"

namespace pathlab {

void SampleOutputs::discard(const Spectrum& value, int s, int t, TechniqueCounters& counters) {
  countDiscarded(value, counters.discarded);
  counters_.noteDiscard(DiscardExample{targets_.id.x, targets_.id.y, targets_.id.sample, s, t, value});
}

void SampleOutputs::splat(int s, int t, Vec2 pRaster, const Spectrum& contribution, TechniqueCounters& counters) {
  const bool accepted = targets_.splats ? targets_.splats->splat(pRaster, contribution)
                                        : !targets_.film || targets_.film->splat(pRaster, contribution);
  if (!accepted) discard(contribution, s, t, counters);
}

void SampleOutputs::trace(const TechniqueResult& r) {
  // The record outlives the kernel's scratch: its pointers are dropped, the path's techniques kept.
  TechniqueResult record = r;
  record.densityRatios = nullptr;
  record.onPath = nullptr;
  record.traced = nullptr;
  targets_.trace->records.push_back(record);
  targets_.trace->onPath.push_back(r.onPath ? *r.onPath : std::vector<TechniqueOnPath>{});
  targets_.trace->paths.push_back(r.traced ? *r.traced : TracedPath{});
}

void SampleOutputs::add(const TechniqueResult& r, TechniqueCounters& counters) {
  if (r.outcome != TechniqueOutcome::Contributed) {
    ++(r.blocked() ? counters.blocked : counters.zero);
    if (targets_.trace) {
      TechniqueResult record = r;
      record.weight = 0.f;
      record.inImage = false;
      trace(record);
    }
    return;
  }
  ++counters.contributed;
  // NaN, Inf and negative contributions are dropped one technique at a time, at the door.
  if (!isValidContribution(r.unweighted)) {
    discard(r.unweighted, r.s, r.t, counters);
    return;
  }
  if (targets_.trace) trace(r);
  // The check compares every enabled technique's unweighted estimate, whatever its weight.
  if (targets_.check) targets_.check->add(Technique{r.s, r.t}, r.pRaster, luminance(r.unweighted), r.sampleableBy, r.densityRatios);
  if (r.inPyramid && targets_.pyramid) {
    const Spectrum weighted = r.unweighted * r.weight;
    // The technique maps' "cannot sample": this path's weighted part, credited to every technique
    // of its length able to sample it. Splats go through the splat buffer if there is one (the
    // render session sums them in a fixed order).
    const bool keepsSampleable = targets_.pyramid->keepsSampleable();
    if (r.t == 1 && targets_.splats) {
      targets_.splats->splatTechnique(r.s, r.pRaster, weighted, r.unweighted);
      if (keepsSampleable) targets_.splats->splatSampleable(r.s, r.sampleableBy, r.pRaster, luminance(weighted));
    } else {
      targets_.pyramid->add(r.s, r.t, r.pRaster, weighted, r.unweighted);
      if (keepsSampleable)
        targets_.pyramid->addSampleable(r.s + r.t - 1, r.sampleableBy, r.pRaster, r.t == 1, luminance(weighted));
    }
  }
  if (!r.inImage) return;
  toImage(r.s, r.t, r.pRaster, r.unweighted * r.imageWeight, counters);
}

}  // namespace pathlab
