// The bidirectional path tracer's per-sample kernel: both subpaths, then every (s, t) in use
// evaluated into a TechniqueResult (unweighted contribution, MIS weight, where it lands) that the
// sample's outputs consume (sample_outputs.h).
#pragma once

#include "core/bpt/bidir_options.h"
#include "core/bpt/mis.h"
#include "core/bpt/mis_partial_sums.h"
#include "core/bpt/sample_outputs.h"
#include "core/bpt/subpath.h"
#include "core/bpt/technique_set.h"

namespace pathlab {

// pbrt-v4 issue 347: the number of light subpaths per pass sets both the t = 1 splat scale
// (Film::finishPass) and the t = 1 sample count in the MIS weight. One light subpath is traced
// per camera sample; this is the only place that says so.
inline constexpr uint64_t kLightSubpathsPerCameraSample = 1;
inline uint64_t lightSubpathsPerPass(uint64_t pixelCount) { return pixelCount * kLightSubpathsPerCameraSample; }
inline float lightTracingRatio() { return static_cast<float>(kLightSubpathsPerCameraSample); }

// How misWeight is computed: decided once per settings change, never per connection.
enum class MisEvaluation {
  PartialSums,  // every technique enabled: O(1) per connection (mis_partial_sums.h)
  Explicit,     // a technique subset: the O(n) walk over the enabled set (mis.h)
};

class BidirTracer {
 public:
  BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options);

  // One camera sample through pRaster and one light subpath: returns the camera-side pixel
  // estimate (t >= 2); the t = 1 contributions, the pyramid and the trace go to `targets`.
  // Contributions that are NaN, Inf or negative are dropped one technique at a time and counted
  // under that technique.
  Spectrum sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                  Counters& counters) const;

  const TechniqueSet& techniques() const { return options_.techniques; }
  MisEvaluation misEvaluation() const { return misEvaluation_; }

  // Time the walks and every technique's connection and weight into the counters, on one camera
  // sample in kTimedSampleStride (Counters::timedSamples counts them). Off by default: when off it
  // costs one branch. Not an estimator option, so switching it never starts a new generation;
  // set it between passes, never during one.
  void setTiming(bool on) { timing_ = on; }
  bool timing() const { return timing_; }

 private:
  struct Walks;  // the per-thread subpaths and their MIS sums
  // Fills r (its s, t, pRaster, inImage and inPyramid already set) with the technique's outcome,
  // contribution and weights.
  void evaluate(TechniqueResult& r, bool enabled, bool unweightedInImage, uint64_t connectionKey, Walks& walks,
                const SampleOutputs& outputs, Counters& counters) const;
  float weight(const MisPath& path, const Walks& walks, Counters& counters) const;

  const Scene& scene_;
  const Camera& camera_;
  BidirOptions options_;
  MisEvaluation misEvaluation_ = MisEvaluation::Explicit;
  MisPower misPower_;
  float minConnectionDistance_ = 0.f;
  int cameraVerticesNeeded_ = 1;  // the camera vertex itself is always there
  int lightVerticesNeeded_ = 0;
  bool timing_ = false;
};

}  // namespace pathlab
