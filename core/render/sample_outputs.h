// Where one bidirectional sample's techniques go in a render: the t = 1 splats onto the film (or
// the thread's splat buffer), the technique pyramid and its maps, a replay trace and the
// consistency check. The kernel (core/bpt/bidir_tracer.h) knows them only as a SampleSink; a new
// output is added here, with what it consumes in its SinkDemand, without touching the kernel.
#pragma once

#include "core/bpt/sample_sink.h"
#include "core/bpt/light_path_choice.h"
#include "core/bpt/optimal_mis.h"
#include "core/bpt/variance_aware_mis.h"
#include "core/check/technique_check.h"
#include "core/film/film.h"
#include "core/film/splat_buffer.h"
#include "core/film/technique_films.h"
#include "core/render/outliers.h"

namespace pathlab {

// The outputs a sample feeds; each may be null.
struct SampleTargets {
  Film* film = nullptr;               // t = 1 splats of the image, atomically
  TechniqueFilms* pyramid = nullptr;  // every technique of the pyramid's lengths, weighted and unweighted
  SampleTrace* trace = nullptr;       // a record of every technique tried
  SampleId id;
  SplatBuffer* splats = nullptr;  // the work item's buffer of the t = 1 splats, instead of `film` and the pyramid's
  TechniqueCheck::PassSums* check = nullptr;  // the thread's sums of the consistency check
  // The outlier finder: every weighted contribution into the thread's heap of the brightest.
  const OutlierTally* outlierTally = nullptr;
  OutlierTally::Heap* outliers = nullptr;
  // Variance-aware MIS: every contribution's unweighted luminance into the factors' pass sums
  // (camera contributions at once, splats into the work item's list, added in the items' order).
  VarianceAwareFactors* varianceAware = nullptr;
  std::vector<VarianceAwareFactors::Splat>* varianceAwareSplats = nullptr;
  // --light-paths auto: every weighted contribution's luminance and light-walk weight into the
  // second moments (camera contributions at once, splats into the work item's list).
  LightPathChoice* lightPaths = nullptr;
  std::vector<LightPathChoice::Splat>* lightPathSplats = nullptr;
  // --mis optimal: every contribution's correction into `film` (camera contributions, at once) or
  // the work item's list (splats, added in the items' order), and into the sums when learning.
  OptimalMis* optimal = nullptr;
  OptimalMis::Splats* optimalSplats = nullptr;
  bool optimalLearns = false;
};

class SampleOutputs final : public SampleSink {
 public:
  explicit SampleOutputs(const SampleTargets& targets);

  void beginSample(std::span<const PathVertex> cameraSubpath, std::span<const PathVertex> lightSubpath) override;
  void walked(int nt, int ns) override;
  void record(const TechniqueResult& result) override;
  // The sample is done: its --light-paths auto sums into its pixel's (nothing without that target).
  void finishSample();

 private:
  bool splat(Vec2 pRaster, const Spectrum& contribution) override;
  void trace(const TechniqueResult& result);
  static SinkDemand demandOf(const SampleTargets& targets);
  const SampleTargets& targets_;
  LightPathChoice::SampleSums lightPathSums_;
};

}  // namespace pathlab
