// The bidirectional kernel's one door: where a sample's techniques go. The kernel (bidir_tracer.h)
// owns this interface; the consumers (the film, the pyramid, the replay trace, the consistency
// check: core/render/sample_outputs.h) implement it, so core/bpt depends on none of them.
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/bpt/technique_result.h"
#include "core/counters/counters.h"
#include "core/math/types.h"

#include <span>

namespace pathlab {

// What a sink consumes beyond the image, fixed when the sink is made (one value per sample, never
// asked per technique). The kernel computes a result's extras only when they are consumed, and
// evaluates the techniques whose records nobody reads without any (its image-only route,
// BidirTracer::imageOnlyPathActive).
struct SinkDemand {
  bool pyramid = false;            // records of the techniques of the pyramid's lengths (BidirOptions::pyramidLength)
  bool everyTechnique = false;     // records of every technique tried, zero and blocked ones too (the replay trace)
  bool everyContribution = false;  // records of every contribution, even where no weight uses it (trace, check)
  // Extras of the records:
  bool onPath = false;         // TechniqueResult::traced and ::onPath (the replay trace)
  bool densityRatios = false;  // TechniqueResult::densityRatios (the consistency check)
  bool sampleable = false;     // TechniqueResult::sampleableBy (the check, the technique maps)
  bool lightWalkWeight = false;  // TechniqueResult::lightWalkWeight (--light-paths auto)
  bool balanceWeights = false;   // TechniqueResult::balanceWeights (--mis optimal)
  // Records of techniques outside the pyramid's lengths.
  bool records() const { return everyTechnique || everyContribution; }
};

class SampleSink {
 public:
  explicit SampleSink(const SinkDemand& demand, SampleId id = {}) : demand_(demand), id_(id) {}
  virtual ~SampleSink() = default;
  SampleSink(const SampleSink&) = delete;
  SampleSink& operator=(const SampleSink&) = delete;

  const SinkDemand& demand() const { return demand_; }
  // Which sample this is: the discarded-contribution report names it (Counters::discardExamples).
  const SampleId& id() const { return id_; }

  // The sample's subpaths, before any technique: the ones every technique shares (path reuse), or
  // none under ConnectStrategy::Endpoints, whose techniques each report their own (walked).
  virtual void beginSample(std::span<const PathVertex> cameraSubpath, std::span<const PathVertex> lightSubpath) {}
  // ConnectStrategy::Endpoints: one technique's own walks gave nt camera and ns light vertices.
  virtual void walked(int nt, int ns) {}
  // A technique's result record, valid (the kernel has refused NaN, Inf and negative contributions
  // and counted them): every technique in the pyramid's lengths, and every one the demand asks for.
  virtual void record(const TechniqueResult& result) {}

  // The image's one route, for the camera estimate and the splats alike: a weighted, valid, non-black
  // contribution of a technique with t camera vertices. t >= 2 lands in the sample's own pixel and is
  // summed here; t = 1 lands at pRaster on the film (splat). Returns false when the film refuses it.
  bool toImage(int t, Vec2 pRaster, const Spectrum& contribution) {
    if (t == 1) return splat(pRaster, contribution);
    cameraEstimate_ += contribution;
    return true;
  }
  // The sum of the sample's t >= 2 contributions: its estimate of its own pixel.
  const Spectrum& cameraEstimate() const { return cameraEstimate_; }

 protected:
  // A t = 1 contribution onto the film at pRaster; false when refused (off the film).
  virtual bool splat(Vec2 pRaster, const Spectrum& contribution) = 0;

 private:
  SinkDemand demand_;
  SampleId id_;
  Spectrum cameraEstimate_{0.f};
};

}  // namespace pathlab
