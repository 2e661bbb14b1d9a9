// Progressive multithreaded rendering: one pass = one camera sample per pixel, tiles in parallel.
// Sample `pass` of pixel (x, y) draws from the stream keyed by (seed, pixel, pass), so any sample
// can be replayed alone, and the splats are summed in a fixed order of tiles (pass_tiles.h), so
// the same seed gives the same image bit for bit at any thread count.
#pragma once

#include "core/bpt/bidir_tracer.h"
#include "core/bpt/light_path_choice.h"
#include "core/check/technique_check.h"
#include "core/film/film.h"
#include "core/film/splat_buffer.h"
#include "core/film/splat_sums.h"
#include "core/film/technique_films.h"
#include "core/mlt/metropolis.h"
#include "core/render/outliers.h"
#include "core/counters/counters.h"
#include "core/pt/path_tracer.h"
#include "core/render/pass_tiles.h"
#include "core/render/render_settings.h"
#include "core/render/sample_outputs.h"
#include "core/scene/scene.h"

#include <atomic>
#include <memory>
#include <span>
#include <vector>

namespace pathlab {

// Which pass indices a session renders: first, first + stride, first + 2 stride, ... Sample i of
// a pixel is keyed by pass index i, so the sessions of N processes given (first = r, stride = N),
// r = 0..N-1, render together exactly the samples of one session rendering all passes.
struct PassSchedule {
  uint64_t first = 0;
  uint64_t stride = 1;
  // The pass index of this session's n-th pass.
  uint64_t pass(uint64_t n) const { return first + stride * n; }
  // How many of the pass indices 0 .. total - 1 are this session's.
  uint64_t passesBelow(uint64_t total) const { return total > first ? (total - first + stride - 1) / stride : 0; }
};

// The random stream of sample `pass` of pixel (x, y): streams are keyed by seed, pixel and pass,
// so any sample can be replayed alone (RenderSession::replaySample, LightSubpathReplay).
Pcg32 sampleStream(const RenderSettings& settings, int x, int y, uint64_t pass, RngStream stream);

class RenderSession {
 public:
  // Throws std::invalid_argument for settings validateSettings refuses.
  RenderSession(const Scene& scene, const RenderSettings& settings, PassSchedule schedule = {});
  ~RenderSession();

  // Renders one more pass over the whole film (blocking; uses the TBB arena of the caller).
  // When *cancel becomes true the pass stops between tiles and false is returned: the film then
  // holds part of a pass and the session must be discarded (a new generation starts afresh).
  bool renderPass(const std::atomic<bool>* cancel = nullptr);
  // The estimate of one camera sample, exactly as renderPass computes it (for replay and tests):
  // the camera-side part is returned; for Bpt and Lt the sample's t = 1 splats go to `splats`
  // if given (a film of the same size, normalised by the caller). With merging techniques the
  // sample's pass is traced again first (every pixel's light subpath, the merge store: costly,
  // as a pass's light walks), once per pass for successive replays of the same pass.
  Spectrum replaySample(int x, int y, uint64_t pass, Counters& counters, Film* splats = nullptr,
                        SampleTrace* trace = nullptr) const;

  // The outlier finder (`pathlab outliers`): from the next pass on, keep the `count` brightest
  // weighted contributions (0: none, the default). Not an estimator option: the image is the
  // same; the samples take the kernel's recording route. Between passes only; bpt, lt and the
  // merging integrators.
  void setOutlierCount(int count);
  // Whether the settings have samples the outlier finder can rank (bpt, lt and the merging integrators).
  bool outliersAvailable() const { return bidirTracer_ && !metropolis_; }
  int outlierCount() const { return outlierTally_ ? outlierTally_->count() : 0; }
  // The brightest contributions so far, brightest first.
  std::vector<Outlier> outliers() const;

  // Per-technique and per-walk timing in the counters (BidirTracer::setTiming); between passes only.
  void setTiming(bool on) {
    if (bidirTracer_) bidirTracer_->setTiming(on);
  }
  // BidirTracer::setImageOnlyPath: off for the benchmark that measures what it saves; between passes only.
  void setImageOnlyPath(bool on) {
    if (bidirTracer_) bidirTracer_->setImageOnlyPath(on);
  }

  const Film& film() const { return film_; }
  Image image() const { return film_.readout(); }
  // Technique (s, t) of the pyramid (settings.pyramidLength > 0), weighted or unweighted.
  bool hasPyramid() const { return pyramid_ != nullptr; }
  // The families the pyramid keeps (pyramidFamilies of the settings in this scene).
  TechniqueFamilies pyramidFamilies() const { return pathlab::pyramidFamilies(settings_, scene_); }
  Image techniqueImage(Technique x, bool unweighted) const;
  // With settings.techniqueMaps: per pixel, the luminance of the length-(s+t-1) image that (s, t)
  // can sample (TechniqueFilms::readoutSampleable).
  std::vector<float> sampleableLuminance(Technique x) const;
  // With settings.varianceMaps: per pixel, the variance of one pass's estimate by (s, t) alone
  // (luminance; TechniqueFilms::readoutVariance), over every pass so far (every rank's, after
  // addForeignPasses).
  std::vector<float> techniqueVariance(Technique x) const;
  // Variance-aware MIS: the factors the next pass weighs with, else null.
  const VarianceAwareFactors* varianceAwareFactors() const { return varianceAware_.get(); }
  // --light-paths auto: the choice so far (its F, candidates' estimates), or null.
  const LightPathChoice* lightPathChoice() const { return lightPathChoice_.get(); }
  // --mis optimal's coefficients (null under the other heuristics).
  const OptimalMis* optimalMis() const { return optimal_.get(); }
  // The consistency check's sums (settings.checkTechniques), else null.
  const TechniqueCheck* techniqueCheck() const { return check_.get(); }
  const Counters& counters() const { return counters_; }
  // Mlt: the chains (their b, acceptance statistics), else null.
  const Metropolis* metropolis() const { return metropolis_.get(); }
  Metropolis* metropolis() { return metropolis_.get(); }
  // Every sum the passes accumulate (film, splats, pyramid), flat arrays of doubles in an order
  // fixed by the settings: sessions with the same settings that rendered disjoint passes combine
  // by adding these element by element, then addForeignPasses. Not concurrent with a pass.
  // Metropolis (Metropolis::sums): its histograms, direct image and counts, the film being written
  // from them; its sessions over ranks all run the same passes, each with its own chains.
  std::vector<std::span<double>> sums();
  // Counts `passes` passes rendered by other sessions whose sums were added to sums(): the film's
  // normalisation and the counters follow; passes() stays this session's own count. (Metropolis:
  // the image is written from the added sums; `passes` is not needed.)
  void addForeignPasses(uint64_t passes, const Counters& counters);
  // This session's own passes (not those of addForeignPasses).
  uint64_t passes() const { return passes_.load(std::memory_order_relaxed); }
  const RenderSettings& settings() const { return settings_; }
  const Camera& camera() const { return camera_; }
  // Pixels finished in the current pass, for progress reporting from another thread.
  uint64_t pixelsDoneInPass() const { return pixelsDone_.load(std::memory_order_relaxed); }

 private:
  const Scene& scene_;
  RenderSettings settings_;
  PassSchedule schedule_;
  Camera camera_;
  PathTracer pathTracer_;
  int cameraMedium_ = -1;  // the medium the camera is in (Scene::mediumAt), for the path tracer
  std::unique_ptr<BidirTracer> bidirTracer_;  // Bpt, Lt and Mlt
  std::unique_ptr<BidirTracer> directTracer_;  // Mlt with MltOptions::directLength: the short paths' techniques
  std::unique_ptr<OutlierTally> outlierTally_;
  std::unique_ptr<Metropolis> metropolis_;    // Mlt: the chains over bidirTracer_'s techniques

  Spectrum sampleAt(int x, int y, uint64_t pass, const SampleTargets& targets, Counters& counters) const;
  Spectrum sampleAt(const BidirTracer* tracer, int x, int y, uint64_t pass, const SampleTargets& targets,
                    Counters& counters) const;
  // Renders one work item's samples: camera estimates into film_, splats into `splats` (Bpt, Lt).
  // `factorSplats`: the item's list of variance-aware MIS splats (or null).
  // `lightPathSplats`: the item's list of --light-paths auto's splats (or null).
  void renderTile(const PassTile& tile, uint64_t pass, SplatBuffer* splats,
                  std::vector<VarianceAwareFactors::Splat>* factorSplats,
                  std::vector<LightPathChoice::Splat>* lightPathSplats, OptimalMis::Splats* optimalSplats,
                  bool optimalLearns, Counters& counters);
  // Vertex merging: every pixel's light subpath of `pass` (the very one its camera sample walks:
  // same stream, same length), stored and indexed for the merges, before the pass's camera samples.
  void traceMergePass(uint64_t pass, Counters& counters);
  // The store of `pass` into `m` (traceMergePass's, and a replay's).
  void buildMergePass(uint64_t pass, Counters& counters, MergePass& m) const;
  std::unique_ptr<MergePass> mergePass_;
  // A replay's merge store, kept for the next replay of the same pass (the inspector steps through
  // one pixel's samples, a test through one pass's pixels); replays may come from any thread.
  struct ReplayStore;
  std::unique_ptr<ReplayStore> replayStore_;
  Film film_;
  std::vector<PassTile> tiles_;  // a pass's work items, in the order their splats are summed
  // The t = 1 splats of the work items in flight (SplatBuffer), then of the current pass in float
  // (SplatSums), merged into film_ when it ends; splatSums_ is null (splats straight into film_,
  // in the same order) when it would take too much memory.
  std::vector<SplatBuffer> tileSplats_;
  // Variance-aware MIS (MisHeuristic::VarianceAware): the factors the weights read, estimated
  // from the passes so far, and each item in flight's splats for their sums (as tileSplats_).
  std::unique_ptr<VarianceAwareFactors> varianceAware_;
  std::vector<std::vector<VarianceAwareFactors::Splat>> factorSplats_;
  // --light-paths auto: the light subpaths per camera sample chosen from the passes so far, and
  // each item in flight's splats for its second moments.
  std::unique_ptr<LightPathChoice> lightPathChoice_;
  std::vector<std::vector<LightPathChoice::Splat>> lightPathSplats_;
  // --mis optimal: the regions' sums and coefficients, and each item in flight's splats.
  std::unique_ptr<OptimalMis> optimal_;
  std::vector<OptimalMis::Splats> optimalSplats_;
  std::unique_ptr<SplatSums> splatSums_;
  std::unique_ptr<TechniqueFilms> pyramid_;
  std::unique_ptr<TechniqueCheck> check_;
  struct ThreadChecks;  // each render thread's sums of the check over the current pass
  std::unique_ptr<ThreadChecks> threadChecks_;
  Counters counters_;
  // Atomic: a progress thread reads it while renderPass runs (`pathlab render`'s progress bar).
  std::atomic<uint64_t> passes_{0};
  std::atomic<uint64_t> pixelsDone_{0};
};

}  // namespace pathlab
