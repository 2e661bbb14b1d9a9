// SampleOutputs: a technique's result into the replay trace, the consistency check, the pyramid
// and, through the kernel's image route, the film.
#include "core/render/sample_outputs.h"

#include "core/bpt/light_paths.h"

#include <algorithm>

namespace pathlab {

SinkDemand SampleOutputs::demandOf(const SampleTargets& targets) {
  SinkDemand d;
  d.pyramid = targets.pyramid != nullptr;
  d.everyTechnique = targets.trace != nullptr;
  // The trace and the check compare every technique's unweighted estimate, whatever its weight.
  // The outlier finder sees every contribution the image receives, through its record.
  // Variance-aware MIS estimates each technique's own variance from every contribution.
  d.everyContribution = targets.trace != nullptr || targets.check != nullptr || targets.outliers != nullptr ||
                        targets.varianceAware != nullptr || targets.lightPaths != nullptr || targets.optimal != nullptr;
  d.onPath = targets.trace != nullptr;
  d.densityRatios = targets.check != nullptr;
  // The replay trace too: the inspector shows it (and the tests compare it with the path's weights).
  d.lightWalkWeight = targets.lightPaths != nullptr || targets.trace != nullptr;
  // The trace too: the inspector recomputes a record's optimal MIS correction with its roulette factor.
  d.balanceWeights = targets.optimal != nullptr || targets.trace != nullptr;
  d.sampleable = targets.check != nullptr || (targets.pyramid != nullptr && targets.pyramid->keepsSampleable());
  return d;
}

SampleOutputs::SampleOutputs(const SampleTargets& targets) : SampleSink(demandOf(targets), targets.id), targets_(targets) {}

void SampleOutputs::beginSample(std::span<const PathVertex> cameraSubpath, std::span<const PathVertex> lightSubpath) {
  lightPathSums_.walked = !lightSubpath.empty();
  SampleTrace* trace = targets_.trace;
  if (!trace) return;
  trace->cameraVertices = static_cast<int>(cameraSubpath.size());
  trace->lightVertices = static_cast<int>(lightSubpath.size());
  trace->records.clear();
  trace->onPath.clear();
  trace->paths.clear();
  trace->cameraSubpath.assign(cameraSubpath.begin(), cameraSubpath.end());
  trace->lightSubpath.assign(lightSubpath.begin(), lightSubpath.end());
}

void SampleOutputs::walked(int nt, int ns) {
  if (!targets_.trace) return;
  targets_.trace->cameraVertices = std::max(targets_.trace->cameraVertices, nt);
  targets_.trace->lightVertices = std::max(targets_.trace->lightVertices, ns);
}

bool SampleOutputs::splat(Vec2 pRaster, const Spectrum& contribution) {
  return targets_.splats ? targets_.splats->splat(pRaster, contribution)
                         : !targets_.film || targets_.film->splat(pRaster, contribution);
}

void SampleOutputs::trace(const TechniqueResult& r) {
  // The record outlives the kernel's scratch: its pointers are dropped, the path's techniques kept.
  TechniqueResult record = r;
  record.densityRatios = nullptr;
  record.onPath = nullptr;
  record.balanceWeights = nullptr;
  record.traced = nullptr;
  targets_.trace->records.push_back(record);
  targets_.trace->onPath.push_back(r.onPath ? *r.onPath : std::vector<TechniqueOnPath>{});
  targets_.trace->paths.push_back(r.traced ? *r.traced : TracedPath{});
}

void SampleOutputs::record(const TechniqueResult& r) {
  if (targets_.trace) trace(r);
  if (r.outcome != TechniqueOutcome::Contributed) return;
  if (targets_.outliers && r.inImage && r.imageWeight > 0.f) {
    const Spectrum v = r.unweighted * r.imageWeight;
    const float y = luminance(v);
    if (y > 0.f) targets_.outlierTally->add(*targets_.outliers, Outlier{y, v, id(), r.technique(), r.pRaster});
  }
  // --light-paths auto: the contribution as the image received it (its 1 / F included).
  if (targets_.lightPaths && r.inImage && r.imageWeight > 0.f)
    targets_.lightPaths->add(r.t, r.kind == TechniqueKind::Connection && usesLightSubpath(r.s, r.t), r.pRaster,
                             luminance(r.unweighted * r.imageWeight), r.lightWalkWeight, lightPathSums_,
                             *targets_.lightPathSplats);
  // --mis optimal: the balance contribution's correction (optimal_mis.h), in the image's units.
  if (targets_.optimal && r.inImage && r.imageWeight > 0.f && r.balanceWeights && r.kind == TechniqueKind::Connection) {
    const Spectrum C = r.unweighted * r.imageWeight;
    const int n = r.s + r.t;
    if (r.t == 1) {
      targets_.optimal->addSplat(r.s, n, r.pRaster, C, r.balanceWeights, *targets_.optimalSplats, r.omittedFactor);
    } else {
      // At the sample's own pixel: pRaster, a float, may round up onto the next pixel, which another
      // work item (another thread) may be rendering.
      const Vec2 pixel(static_cast<float>(id().x) + 0.5f, static_cast<float>(id().y) + 0.5f);
      const Spectrum correction =
          targets_.optimal->addCamera(r.s, n, pixel, C, r.balanceWeights, targets_.optimalLearns, r.omittedFactor);
      if (targets_.film && !isBlack(correction)) targets_.film->addCorrection(id().x, id().y, correction);
    }
  }
  if (targets_.varianceAware)
    targets_.varianceAware->add(r.technique(), r.pRaster, luminance(r.unweighted), *targets_.varianceAwareSplats);
  // The check compares every enabled technique's unweighted estimate, whatever its weight.
  if (targets_.check) targets_.check->add(r.technique(), r.pRaster, luminance(r.unweighted), r.sampleableBy, r.densityRatios);
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
      targets_.pyramid->add(r.technique(), r.pRaster, weighted, r.unweighted);
      if (keepsSampleable)
        targets_.pyramid->addSampleable(r.technique().length(), r.sampleableBy, r.pRaster, r.t == 1, luminance(weighted));
    }
  }
}

void SampleOutputs::finishSample() {
  if (targets_.lightPaths) targets_.lightPaths->addCameraSample(id().x, id().y, lightPathSums_);
}

}  // namespace pathlab
