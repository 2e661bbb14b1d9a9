// The bidirectional path tracer's per-sample kernel: both subpaths, then every (s, t) in use
// evaluated once, by one function (evaluate), into the sample's sink (sample_sink.h): the image's
// contributions, and the result records (unweighted contribution, MIS weight, where it lands) of
// the techniques the sink consumes.
#pragma once

#include "core/bpt/bidir_options.h"
#include "core/bpt/light_paths.h"
#include "core/bpt/mis.h"
#include "core/bpt/merge_mis.h"
#include "core/bpt/merge_pass.h"
#include "core/bpt/mis_partial_sums.h"
#include "core/bpt/sample_sink.h"
#include "core/bpt/subpath.h"
#include "core/bpt/technique_set.h"
#include "core/bpt/variance_aware_mis.h"

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

struct Connection;  // connect.h

class BidirTracer {
 public:
  BidirTracer(const Scene& scene, const Camera& camera, const BidirOptions& options);

  // One camera sample through pRaster and one light subpath (ConnectStrategy::Endpoints: a
  // camera and a light subpath per technique), every technique in use into `sink`: its estimate of
  // the pixel (SampleSink::cameraEstimate) and its splats through SampleSink::toImage, its records
  // as the sink's demand asks. Contributions that are NaN, Inf or negative are dropped one technique
  // at a time, at the kernel's door, and counted under that technique.
  // Rng: Pcg32, or the camera and light streams of a primary sample vector (Metropolis over the
  // whole sample, core/mlt/metropolis.h; its connections' numbers still come from the key the
  // camera stream gives, connectionStream).
  template <class Rng>
  void sample(Vec2 pRaster, Vec2 uLens, Rng& cameraRng, Rng& lightRng, SampleSink& sink, Counters& counters) const;

  // Multiplexed Metropolis (Hachisuka, Kaplanyan and Dachsbacher 2014; core/mlt/metropolis.h):
  // technique (s, t) alone, on a camera subpath of exactly t vertices through pRaster and a light
  // subpath of exactly s (no light walk for next-event estimation, s = 1 with t >= 2, whose light
  // point the connection samples), every number drawn from the primary sample's streams. Its
  // contribution weighted over the enabled set, as in the image (zero when a walk ended early, the
  // technique cannot form the path or the connection is blocked), and where it lands: pRaster, or
  // the t = 1 splat's position. The technique need not be enabled; its weight is then zero.
  // `records` (or null): the sink that gets the subpaths walked (beginSample, also when a walk
  // ended early) and the technique's record, with the extras its demand asks for (the Metropolis
  // chains' paths in the 3D view, `pathlab inspect` on a chain's state).
  struct TechniqueSample {
    Spectrum L{0.f};
    Vec2 pRaster{0.f};
  };
  TechniqueSample sampleTechnique(int s, int t, Vec2 pRaster, Vec2 uLens, PrimarySampleStream& cameraRng,
                                  PrimarySampleStream& lightRng, PrimarySampleStream& connectionRng,
                                  Counters& counters, SampleSink* records = nullptr) const;

  // The light subpath this tracer walks for a sample whose light stream is `lightRng` (path reuse:
  // the one every technique of the sample shares; ConnectStrategy::Endpoints draws one per technique
  // from other streams, so this is one of the same distribution), appended to `out`: the viewer's
  // light particles, a merge pass's store. Returns its vertex count (0 when no technique needs a
  // light walk).
  int traceLightSubpath(Pcg32& lightRng, std::vector<PathVertex>& out, Counters& counters) const;

  const TechniqueSet& techniques() const { return options_.techniques; }

  // Vertex merging (merge_pass.h): whether the technique set has merges, and the pass's stored
  // light subpaths they merge with, set between passes (never during one). Each camera vertex
  // z(t-1), t >= 2, merges with every stored light vertex within the pass's radius; every weight,
  // connections' included, is then the explicit one over connections and merges (merge_mis.h).
  bool merges() const { return merges_; }
  void setMergePass(const MergePass* pass) { mergePass_ = pass; }
  // The MIS partial sums of `pass`'s light subpaths (MergePass::misSum, accumulateLightSums'
  // pointer form, with the pass's eta: what a camera sample's connections to its own light subpath
  // read) and each record's light terms (MergeRecord::mis, what a merge reads), in parallel, after
  // MergePass::index. Nothing when the weights are explicit.
  void prepareMergePass(MergePass& pass) const;
  MisEvaluation misEvaluation() const { return misEvaluation_; }
  // Variance-aware MIS (MisHeuristic::VarianceAware): the factors every weight reads from now on
  // (null: all 1, the balance heuristic); set between passes, never during one.
  void setVarianceAwareFactors(const VarianceAwareFactors* factors) { varianceAware_ = factors; }
  // --light-paths auto (light_path_choice.h): light subpaths per camera sample from now on, in the
  // walks, the contributions' scale and every weight's counts (light_paths.h); set between passes,
  // never during one.
  void setLightPaths(float lightPaths);
  float lightPaths() const { return options_.lightPaths; }

  // Time the walks and every technique's connection and weight into the counters, on one camera
  // sample in kTimedSampleStride (Counters::timedSamples counts them). Off by default: when off it
  // costs one branch. Not an estimator option, so switching it never starts a new generation;
  // set it between passes, never during one.
  void setTiming(bool on) { timing_ = on; }
  bool timing() const { return timing_; }

  // The image-only route: a sample whose sink consumes only the image (SinkDemand::records() false)
  // evaluates its techniques outside the pyramid without a result record, by the same evaluate()
  // compiled without it. On by default wherever the settings allow (the partial sums, no media, no
  // isolation, MIS check or injected bias; ConnectStrategy::Endpoints never takes it). Off sends
  // every technique through the recording instance: the test oracle of the route and its
  // benchmark's baseline. Like timing, set it between passes.
  void setImageOnlyPath(bool on) { imageOnlyPathOff_ = !on; }
  bool imageOnlyPathActive() const { return imageOnlyPath_ && !imageOnlyPathOff_; }

 private:
  struct Walks;  // the per-thread subpaths and their MIS sums
  // How a technique is used by this sample: whether it is enabled (weighed), reaches the image
  // (enabled, or the isolated one), is shown unweighted (--isolate --unweighted) and goes to the
  // pyramid.
  struct TechniqueUse {
    bool enabled = true, inImage = true, unweightedInImage = false, inPyramid = false;
    bool used() const { return inImage || inPyramid; }
  };
  TechniqueUse techniqueUse(int s, int t, int pyramidLength) const;
  TechniqueUse techniqueUse(Technique x, int pyramidLength) const;
  // The one evaluation of technique (s, t): forms the connection, weighs it, traces its shadow ray,
  // reports each outcome to the tally (counts, time), refuses an invalid contribution, and hands
  // the result to the sink: its record when kRecords, its weighted contribution to the image.
  // kRecords false is the image-only route (a sink with no records, a technique outside the
  // pyramid, imageOnlyPathActive()): the compiler drops the record and the extras it would fill.
  // ConnectionRng Pcg32: the connection's fresh endpoint (s = 1, t = 1) comes from its stream keyed
  // by connectionKey (connectionStream); PrimarySampleStream: from *connectionRng, the Metropolis
  // state's connection stream (sampleTechnique).
  template <bool kRecords, bool kTimed, class ConnectionRng = Pcg32>
  void evaluate(int s, int t, const TechniqueUse& use, Vec2 pRaster, uint64_t connectionKey, Walks& walks,
                SampleSink& sink, Counters& counters, ConnectionRng* connectionRng = nullptr) const;
  template <bool kRecords>
  void evaluate(bool timed, int s, int t, const TechniqueUse& use, Vec2 pRaster, uint64_t connectionKey, Walks& walks,
                SampleSink& sink, Counters& counters) const;
  // The walks of both strategies (rays into the counters' walk or technique rows by the caller).
  template <class Rng>
  int walkCamera(Vec2 pRaster, Vec2 uLens, int vertices, Rng& rng, Walks& walks, Counters& counters) const;
  template <class Rng>
  int walkLight(int vertices, Rng& rng, Walks& walks, Counters& counters) const;
  // ConnectStrategy::Endpoints: each technique in use on subpaths of its own.
  void sampleEndpoints(Vec2 pRaster, Vec2 uLens, uint64_t connectionKey, bool timed, int pyramidLength, Walks& walks,
                       SampleSink& sink, Counters& counters) const;
  // The MIS weight of technique (s, t) on the connection just formed (misEvaluation_); kRecords as
  // evaluate's (false: the image-only route, whose preconditions fix the partial sums).
  template <bool kRecords>
  // `factors`: variance-aware MIS's where the path lands (null: all 1).
  float weight(const MisPath& path, const Connection& c, const Walks& walks, const float* factors,
               Counters& counters) const;
  // The equiangular techniques E(1, t) of the sample's camera subpath (equiangular_technique.h),
  // each as evaluate does a connection: its use (switch, isolation, pyramid), tally, record and
  // image share.
  void evaluateEquiangular(Vec2 pRaster, uint64_t connectionKey, int pyramidLength, Walks& walks, SampleSink& sink,
                           Counters& counters) const;
  // The sample's light subpath from the merge pass into walks.light; its vertex count.
  int storedLightSubpath(const SampleId& id, Walks& walks) const;
  // The merges of the sample's camera subpath (nt vertices) with the pass's light vertices.
  // Every merge at the camera vertices; timed: the search's time to Counters::mergeSearch, each
  // merge's own to its technique.
  void evaluateMerges(bool timed, int nt, Vec2 pRaster, int pyramidLength, Walks& walks, SampleSink& sink,
                      Counters& counters) const;
  template <bool kTimed>
  void evaluateMerges(int nt, Vec2 pRaster, int pyramidLength, Walks& walks, SampleSink& sink, Counters& counters) const;
  // The inspector's view of a merge M(s, t) (its vertices, traced path and every technique's
  // density and weight on its merged path) into `r`: out of evaluateMerges' loop, which a render
  // runs without it.
  // `factors`: variance-aware MIS's, where the merge lands (or null).
  [[gnu::cold]] void inspectMerge(const MergePass& pass, uint32_t lightVertex, int s, int t, const MergePdfs& pdfs,
                                  const float* factors,
                                  Walks& walks, TechniqueResult& r) const;
  // The merges' part of the partial sums for this pass (its eta and keep probability).
  MergeTerms mergeTerms(const MergePass& pass) const;
  bool lightWalkNeeded(int s, int t) const { return usesLightSubpath(s, t); }  // NEE draws its own

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
  bool imageOnlyPath_ = false;     // the image-only route's preconditions that the settings decide
  bool imageOnlyPathOff_ = false;  // setImageOnlyPath(false)
  bool merges_ = false;
  // The equiangular family is sampled: options_.mis.mediumSampling is not Distance (it is reset to
  // Distance where E cannot run: no homogeneous scattering medium, merges, naive BPT).
  bool equiangular_ = false;
  double connectionsInSums_ = 1.0;  // MergeTerms::connections: every connection enabled, or none
  const MergePass* mergePass_ = nullptr;
  const VarianceAwareFactors* varianceAware_ = nullptr;
  // --light-paths F < 1 (light_paths.h): each technique's samples per camera sample by
  // Technique::index (empty at F = 1), and 1 / F, the light-walk techniques' contribution scale.
  std::vector<float> lightPathCounts_;
  float lightPathScale_ = 1.f;
  const float* lightPathCountsOfLength(int k) const {
    return lightPathCounts_.empty() ? nullptr : lightPathCounts_.data() + Technique::firstIndexOfLength(k);
  }
  // Whether the walks keep each vertex's step and count for weights with per-technique counts
  // (SubpathMisSums::step): variance-aware factors or light-path counts.
  bool countsInWeights() const { return varianceAware_ != nullptr || !lightPathCounts_.empty(); }
};

extern template void BidirTracer::sample(Vec2, Vec2, Pcg32&, Pcg32&, SampleSink&, Counters&) const;
extern template void BidirTracer::sample(Vec2, Vec2, PrimarySampleStream&, PrimarySampleStream&, SampleSink&,
                                         Counters&) const;

}  // namespace pathlab
