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

#include <vector>

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
  Constant,     // MisHeuristic::Off: 1 / n_k from a table by length (mis_off.h)
};

class BidirTracer {
 public:
  BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options);

  // One camera sample through pRaster and one light subpath (ConnectStrategy::Endpoints: a
  // camera and a light subpath per technique): returns the camera-side pixel estimate (t >= 2);
  // the t = 1 contributions, the pyramid and the trace go to `targets`.
  // Contributions that are NaN, Inf or negative are dropped one technique at a time and counted
  // under that technique.
  Spectrum sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                  Counters& counters) const;

  // The light subpath this tracer walks for a sample whose light stream is `lightRng` (path reuse:
  // the one every technique of the sample shares; ConnectStrategy::Endpoints draws one per technique
  // from other streams, so this is one of the same distribution), into `out`: the viewer's light
  // particles. Returns its vertex count (0 when no technique needs a light walk).
  int traceLightSubpath(Pcg32& lightRng, std::vector<PathVertex>& out, Counters& counters) const;

  const TechniqueSet& techniques() const { return options_.techniques; }
  MisEvaluation misEvaluation() const { return misEvaluation_; }

  // Time the walks and every technique's connection and weight into the counters, on one camera
  // sample in kTimedSampleStride (Counters::timedSamples counts them). Off by default: when off it
  // costs one branch. Not an estimator option, so switching it never starts a new generation;
  // set it between passes, never during one.
  void setTiming(bool on) { timing_ = on; }
  bool timing() const { return timing_; }

  // The image-only path (runImageOnly): on by default wherever the settings allow it (the partial
  // sums, no media, no isolation, MIS check or injected bias; ConnectStrategy::Endpoints never
  // uses it). Off sends every technique through the general evaluate(): its test oracle and its
  // benchmark's baseline. Like timing, set it between passes.
  void setImageOnlyPath(bool on) { imageOnlyPathOff_ = !on; }
  // Whether samples whose outputs allow it (SampleOutputs::imageOnly) take the image-only path.
  bool imageOnlyPathActive() const { return imageOnlyPath_ && !imageOnlyPathOff_; }

 private:
  struct Walks;  // the per-thread subpaths and their MIS sums
  // Sets r's s, t, pRaster, inImage and inPyramid; false when nothing uses the technique.
  bool prepare(TechniqueResult& r, int s, int t, Vec2 pRaster, int pyramidLength) const;
  // Counts, times and evaluates a prepared technique and hands the result to the outputs.
  void run(TechniqueResult& r, uint64_t connectionKey, bool timed, Walks& walks, SampleOutputs& outputs,
           Counters& counters) const;
  // The walks of both strategies (rays into the counters' walk or technique rows by the caller).
  int walkCamera(Vec2 pRaster, Vec2 uLens, int vertices, Pcg32& rng, Walks& walks, Counters& counters) const;
  int walkLight(int vertices, Pcg32& rng, Walks& walks, Counters& counters) const;
  // ConnectStrategy::Endpoints: each technique in use on subpaths of its own.
  void sampleEndpoints(Vec2 pRaster, Vec2 uLens, uint64_t connectionKey, bool timed, int pyramidLength, Walks& walks,
                       SampleOutputs& outputs, const SampleTargets& targets, Counters& counters) const;
  // Fills r (its s, t, pRaster, inImage and inPyramid already set) with the technique's outcome,
  // contribution and weights.
  void evaluate(TechniqueResult& r, bool enabled, bool unweightedInImage, uint64_t connectionKey, Walks& walks,
                const SampleOutputs& outputs, Counters& counters) const;
  float weight(const MisPath& path, const Walks& walks, Counters& counters) const;
  // evaluate(), run() and SampleOutputs::add() of a technique whose result goes only to the image
  // and the counters (imageOnlyPathActive(), SampleOutputs::imageOnly(), the technique not in the
  // pyramid): the same connection, shadow ray and partial-sums weight in the same order, hence the
  // same image, counters, discards and timing (tests/bpt_image_only_path_test.cpp), without the
  // result record, the outputs' fan-out and, for the interior techniques (s, t >= 2), the dispatch
  // on s and t (formInteriorConnection, misWeightInterior). docs/benchmarks.md, session 13.
  // kTimed: a timed sample's (setTiming), whose technique time it adds up as run() does.
  template <bool kTimed>
  void runImageOnly(int s, int t, uint64_t connectionKey, Walks& walks, SampleOutputs& outputs, Counters& counters) const;
  bool lightWalkNeeded(int s, int t) const { return s >= 1 && !(s == 1 && t >= 2); }  // NEE draws its own

  const Scene& scene_;
  const Camera& camera_;
  BidirOptions options_;
  MisEvaluation misEvaluation_ = MisEvaluation::Explicit;
  MisPower misPower_;
  std::vector<float> offWeights_;  // MisEvaluation::Constant: 1 / n_k by length k
  float minConnectionDistance_ = 0.f;
  int cameraMedium_ = -1;  // the medium the camera is in (Scene::mediumAt), where its walks start
  int cameraVerticesNeeded_ = 1;  // the camera vertex itself is always there
  int lightVerticesNeeded_ = 0;
  bool timing_ = false;
  bool imageOnlyPath_ = false;     // runImageOnly's preconditions that the settings decide
  bool imageOnlyPathOff_ = false;  // setImageOnlyPath(false)
};

}  // namespace pathlab
