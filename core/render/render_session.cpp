// Passes over the work items (pass_tiles.h) with a TBB pipeline: rendered in parallel, their
// splats added in the items' order; per-thread counters merged after each pass.
#include "core/render/render_session.h"

#include "core/counters/technique_timer.h"
#include "core/merge/room.h"
#include "core/render/variance_aware_regions.h"

#include <tbb/global_control.h>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace pathlab {

namespace {
// The pass's splat sums in float (SplatSums) up to this much memory; beyond it (an image of over
// 44 million pixels) each work item's splats go straight into the film's doubles, in the same order.
constexpr size_t kMaxSplatSumBytes = size_t{512} << 20;
// Work items in flight: the splats of an item wait for those of the items before it, so an item
// that is slow (or whose thread the system put aside for a while, on a loaded machine) lets the
// other threads run this many items ahead before they idle; each holds its splats meanwhile (about
// 64 KiB an item of 1,024 samples on the Cornell box, 340 KiB with a pyramid and technique maps).
constexpr size_t kItemsInFlightPerThread = 4;
constexpr size_t kMinItemsInFlight = 32;

// The threads a pass runs on: the arena's, or fewer when a tbb::global_control limits them
// (`--threads`), which the arena's max_concurrency does not report.
int activeThreads() {
  const size_t limit = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  // No limit set reads as SIZE_MAX: clamped to an int before the comparison.
  const int limited = static_cast<int>(std::min<size_t>(limit, static_cast<size_t>(std::numeric_limits<int>::max())));
  return std::max(1, std::min(tbb::this_task_arena::max_concurrency(), limited));
}

const RenderSettings& validated(const RenderSettings& settings, const Scene& scene) {
  validateSettings(settings);
  validateSettingsForCamera(settings, scene.cameraDesc());
  return settings;
}

PassSchedule validated(PassSchedule schedule) {
  if (schedule.stride == 0) throw std::invalid_argument("a pass schedule's stride must be at least 1");
  return schedule;
}
}  // namespace

struct RenderSession::ThreadChecks {
  tbb::enumerable_thread_specific<TechniqueCheck::PassSums> sums;
  explicit ThreadChecks(const TechniqueCheck& check) : sums(TechniqueCheck::PassSums(check)) {}
};

struct RenderSession::ReplayStore {
  std::mutex mutex;
  std::shared_ptr<const MergePass> store;
  uint64_t pass = 0;
};

RenderSession::~RenderSession() = default;

RenderSession::RenderSession(const Scene& scene, const RenderSettings& settings, PassSchedule schedule)
    : scene_(scene),
      settings_(validated(settings, scene)),
      schedule_(validated(schedule)),
      camera_(settings.camera.value_or(scene.cameraDesc()), settings.width, settings.height, settings.lens),
      pathTracer_(scene, pathTracerOptions(settings)),
      cameraMedium_(scene.mediumAt(camera_.position())),
      film_(settings.width, settings.height),
      tiles_(passTiles(settings.width, settings.height)) {
  replayStore_ = std::make_unique<ReplayStore>();
  const int directLength = settings_.integrator == IntegratorKind::Mlt ? settings_.mlt.directLength : 0;  // <= maxLength
  if (directLength > 0) {
    // Metropolis with its short paths by BPT (MltOptions::directLength): the chains' tracer keeps
    // the longer techniques, a second tracer the shorter ones. The MIS weights of a technique
    // involve only those of its own length, so each keeps its weights.
    BidirOptions chains = bidirOptions(settings_), direct = chains;
    for (int k = 1; k <= settings_.maxLength; ++k)
      (k <= directLength ? chains : direct).techniques.disable(TechniqueSet::ofLength(k), settings_.maxLength);
    direct.maxLength = directLength;
    bidirTracer_ = std::make_unique<BidirTracer>(scene, camera_, chains);
    directTracer_ = std::make_unique<BidirTracer>(scene, camera_, direct);
  } else if (settings.integrator != IntegratorKind::Pt) {
    bidirTracer_ = std::make_unique<BidirTracer>(scene, camera_, bidirOptions(settings));
  }
  // Metropolis over ranks: every rank runs every pass, with its share of the chains (MltRanks).
  if (settings.integrator == IntegratorKind::Mlt)
    metropolis_ = std::make_unique<Metropolis>(
        *bidirTracer_, settings.width, settings.height, settings.maxLength, settings.seed, settings.mlt,
        directTracer_.get(), MltRanks{static_cast<int>(schedule_.first), static_cast<int>(schedule_.stride)});
  // (Metropolis keeps histograms of its own: no pass sums.)
  if (bidirTracer_ && !metropolis_ && SplatSums::bytesFor(settings.width, settings.height) <= kMaxSplatSumBytes)
    splatSums_ = std::make_unique<SplatSums>(settings.width, settings.height);
  if (bidirTracer_ && settings.pyramidLength > 0)
    pyramid_ = std::make_unique<TechniqueFilms>(settings.width, settings.height, settings.pyramidLength,
                                                settings.techniqueMaps, pathlab::pyramidFamilies(settings, scene),
                                                settings.varianceMaps);
  if (bidirTracer_ && !metropolis_ && settings.mis.heuristic == MisHeuristic::VarianceAware) {
    VarianceAwareRegions regions = varianceAwareRegions(settings.width, settings.height, tiles_,
                                                        varianceAwareCell(settings.width, settings.height, settings.maxLength));
    varianceAware_ = std::make_unique<VarianceAwareFactors>(settings.width, settings.height,
                                                            std::move(regions.regionOfPixel), regions.count,
                                                            settings.maxLength);
    bidirTracer_->setVarianceAwareFactors(varianceAware_.get());
  }
  // In a scene with media the correction would be biased (validateSettingsForScene): the commands
  // refuse it before they get here; the viewer's sessions render the balance heuristic and its
  // status says so (optimalMisWarning).
  if (bidirTracer_ && !metropolis_ && settings.mis.heuristic == MisHeuristic::Optimal && !scene.hasMedia()) {
    VarianceAwareRegions regions = varianceAwareRegions(settings.width, settings.height, tiles_,
                                                        optimalMisCell(settings.width, settings.height, settings.maxLength));
    optimal_ = std::make_unique<OptimalMis>(
        settings.width, settings.height, std::move(regions.regionOfPixel), regions.count, settings.maxLength,
        settings.lightPaths,
        static_cast<double>(film_.pixelCount()) / static_cast<double>(lightSubpathsPerPass(film_.pixelCount())));
  }
  if (bidirTracer_ && !metropolis_ && settings.lightPathsAuto)
    lightPathChoice_ = std::make_unique<LightPathChoice>(settings.width, settings.height, settings.lightPaths);
  if (bidirTracer_ && settings.checkTechniques) {
    const TechniqueSet enabled = enabledTechniques(settings);
    check_ = std::make_unique<TechniqueCheck>(settings.width, settings.height, settings.maxLength, settings.checkBlocks,
                                              [&](Technique x) { return enabled.contains(x); },
                                              sampledFamilies(settings, scene));
    threadChecks_ = std::make_unique<ThreadChecks>(*check_);
  }
}

Spectrum RenderSession::replaySample(int x, int y, uint64_t pass, Counters& counters, Film* splats,
                                     SampleTrace* trace) const {
  const SampleTargets targets{splats, nullptr, trace, SampleId{x, y, pass}};
  if (!bidirTracer_ || !bidirTracer_->merges()) return sampleAt(x, y, pass, targets, counters);
  // A merge needs its pass's every light subpath, which no sample keeps: the pass's store is built
  // again from the same per-pixel streams, in the same order (buildMergePass), so the sample finds
  // the same light vertices within the same radius in the same order as the render did, and its
  // merges are the render's bit for bit. The walks' rays are the pass's, not the sample's: they are
  // not counted.
  std::shared_ptr<const MergePass> store;
  {
    std::lock_guard<std::mutex> lock(replayStore_->mutex);
    if (!replayStore_->store || replayStore_->pass != pass) {
      auto built = std::make_shared<MergePass>();
      Counters walks;
      buildMergePass(pass, walks, *built);
      replayStore_->store = std::move(built);
      replayStore_->pass = pass;
    }
    store = replayStore_->store;
  }
  // A tracer of its own: the session's points at the store of the pass being rendered.
  BidirTracer tracer = *bidirTracer_;
  tracer.setMergePass(store.get());
  return sampleAt(&tracer, x, y, pass, targets, counters);
}

Pcg32 sampleStream(const RenderSettings& settings, int x, int y, uint64_t pass, RngStream stream) {
  const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(settings.width) + static_cast<uint64_t>(x);
  return makeSampleRng(settings.seed, pixel, pass, stream);
}

Image RenderSession::techniqueImage(Technique x, bool unweighted) const {
  if (!pyramid_) return Image{film_.width(), film_.height(), std::vector<float>(3 * film_.pixelCount(), 0.f)};
  return pyramid_->readout(x, unweighted, film_.samplesPerPixel(), film_.lightSubpaths());
}

void RenderSession::setOutlierCount(int count) {
  if (count > 0 && !outliersAvailable())
    throw std::invalid_argument("the outlier finder needs independent bidirectional samples (bpt, lt, vcm, bpm, ppm)");
  outlierTally_ = count > 0 ? std::make_unique<OutlierTally>(count) : nullptr;
}

std::vector<Outlier> RenderSession::outliers() const { return outlierTally_ ? outlierTally_->top() : std::vector<Outlier>{}; }

std::vector<float> RenderSession::techniqueVariance(Technique x) const {
  if (!pyramid_) return std::vector<float>(film_.pixelCount(), 0.f);
  return pyramid_->readoutVariance(x, film_.samplesPerPixel(), film_.samplesPerPixel(), film_.lightSubpaths());
}

std::vector<float> RenderSession::sampleableLuminance(Technique x) const {
  if (!pyramid_) return std::vector<float>(film_.pixelCount(), 0.f);
  return pyramid_->readoutSampleable(x, film_.samplesPerPixel(), film_.lightSubpaths());
}

std::vector<std::span<double>> RenderSession::sums() {
  if (metropolis_) return metropolis_->sums();  // the film is written from them
  std::vector<std::span<double>> all;
  for (std::span<double> s : film_.sums()) all.push_back(s);
  if (pyramid_)
    for (std::span<double> s : pyramid_->sums()) all.push_back(s);
  return all;
}

void RenderSession::addForeignPasses(uint64_t passes, const Counters& counters) {
  if (metropolis_) {
    // Every rank ran every pass with its own chains: the job's image from the added sums.
    metropolis_->sumsCombined();
    metropolis_->writeImage(film_);
    counters_ += counters;
    return;
  }
  film_.finishPass(passes, bidirTracer_ ? passes * lightSubpathsPerPass(film_.pixelCount()) : 0);
  counters_ += counters;
}

Spectrum RenderSession::sampleAt(int x, int y, uint64_t pass, const SampleTargets& targets, Counters& counters) const {
  return sampleAt(bidirTracer_.get(), x, y, pass, targets, counters);
}

Spectrum RenderSession::sampleAt(const BidirTracer* tracer, int x, int y, uint64_t pass, const SampleTargets& targets,
                                 Counters& counters) const {
  Pcg32 rng = sampleStream(settings_, x, y, pass, RngStream::Camera);
  const Vec2 uFilm = rng.next2D();  // box filter: uniform over the pixel
  const Vec2 uLens = rng.next2D();
  const Vec2 pRaster = Vec2(static_cast<float>(x), static_cast<float>(y)) + uFilm;
  ++counters.cameraSamples;
  if (tracer) {
    Pcg32 lightRng = sampleStream(settings_, x, y, pass, RngStream::Light);
    SampleOutputs outputs(targets);
    tracer->sample(pRaster, uLens, rng, lightRng, outputs, counters);
    outputs.finishSample();
    return outputs.cameraEstimate();
  }
  const Ray ray = camera_.generateRay(pRaster, uLens);
  return pathTracer_.Li(ray, rng, counters, cameraMedium_);
}

void RenderSession::renderTile(const PassTile& tile, uint64_t pass, SplatBuffer* splats,
                               std::vector<VarianceAwareFactors::Splat>* factorSplats,
                               std::vector<LightPathChoice::Splat>* lightPathSplats,
                               OptimalMis::Splats* optimalSplats, bool optimalLearns, Counters& c) {
  SampleTargets targets{&film_, pyramid_.get(), nullptr, {}};
  targets.splats = splats;
  if (varianceAware_ && factorSplats) targets.varianceAware = varianceAware_.get(), targets.varianceAwareSplats = factorSplats;
  if (lightPathChoice_ && lightPathSplats) targets.lightPaths = lightPathChoice_.get(), targets.lightPathSplats = lightPathSplats;
  if (optimal_ && optimalSplats)
    targets.optimal = optimal_.get(), targets.optimalSplats = optimalSplats, targets.optimalLearns = optimalLearns;
  targets.check = threadChecks_ ? &threadChecks_->sums.local() : nullptr;
  if (outlierTally_) targets.outlierTally = outlierTally_.get(), targets.outliers = &outlierTally_->local();
  for (int y = tile.y0; y < tile.y1; ++y)
    for (int x = tile.x0; x < tile.x1; ++x) {
      targets.id = SampleId{x, y, pass};
      const Spectrum L = sampleAt(x, y, pass, targets, c);
      if (!film_.addSample(x, y, L)) {
        countDiscarded(L, c);
        c.noteDiscard(DiscardExample{x, y, pass, -1, -1, L});
      }
    }
  pixelsDone_.fetch_add(static_cast<uint64_t>(tile.pixels()), std::memory_order_relaxed);
}

void RenderSession::traceMergePass(uint64_t pass, Counters& counters) {
  if (!mergePass_) mergePass_ = std::make_unique<MergePass>();
  buildMergePass(pass, counters, *mergePass_);
  bidirTracer_->setMergePass(mergePass_.get());
}

void RenderSession::buildMergePass(uint64_t pass, Counters& counters, MergePass& m) const {
  // Each work item walks its pixels' light subpaths into a list of its own; the lists are indexed
  // in item order, so the store (and the order of every merge) is the same at any thread count.
  // Serial work: one offset per item. The lists keep their memory from pass to pass
  // (MergePass::walkItems).
  m.walkItems.resize(tiles_.size());
  tbb::enumerable_thread_specific<Counters> local;
  tbb::parallel_for(size_t{0}, tiles_.size(), [&](size_t i) {
    const PassTile& tile = tiles_[i];
    MergePass::WalkItem& out = m.walkItems[i];
    // Walked into a scratch list of the thread's, then copied into the item's with a quarter of
    // headroom: a list grown by doubling would keep up to twice its vertices' memory.
    thread_local std::vector<PathVertex> walked;
    walked.clear();
    out.pixels.clear();
    out.pixelStart.clear();
    out.pixelCount.clear();
    Counters& c = local.local();
    for (int y = tile.y0; y < tile.y1; ++y)
      for (int x = tile.x0; x < tile.x1; ++x) {
        Pcg32 lightRng = sampleStream(settings_, x, y, pass, RngStream::Light);
        const uint64_t raysBefore = c.rays;
        out.pixels.push_back(static_cast<uint32_t>(y) * static_cast<uint32_t>(settings_.width) + static_cast<uint32_t>(x));
        out.pixelStart.push_back(static_cast<uint32_t>(walked.size()));
        const int n = bidirTracer_->traceLightSubpath(lightRng, walked, c);
        c.mergePass.rays += c.rays - raysBefore;
        out.pixelCount.push_back(static_cast<uint32_t>(n));
      }
    resizeWithRoom(out.vertices, walked.size());
    std::copy(walked.begin(), walked.end(), out.vertices.begin());
  });
  for (const Counters& c : local) counters += c;
  // The paths stay where the walks wrote them (MergePass::walkItems); the pass's indices count
  // through the items in order.
  const std::vector<MergePass::WalkItem>& items = m.walkItems;
  std::vector<size_t> offset(items.size() + 1, 0);
  for (size_t i = 0; i < items.size(); ++i) offset[i + 1] = offset[i] + items[i].vertices.size();
  if (offset.back() >= UINT32_MAX) throw std::runtime_error("vertex merging: too many light vertices in one pass");
  m.itemStart.assign(offset.begin(), offset.end());
  resizeWithRoom(m.pathStart, offset.back());
  m.width = settings_.width;
  m.pixelPathStart.assign(film_.pixelCount(), 0);
  m.pixelPathCount.assign(film_.pixelCount(), 0);
  m.pixelPath.assign(film_.pixelCount(), nullptr);
  tbb::parallel_for(size_t{0}, items.size(), [&](size_t i) {
    const MergePass::WalkItem& item = items[i];
    const uint32_t base = static_cast<uint32_t>(offset[i]);
    for (size_t j = 0; j < item.pixels.size(); ++j) {
      const uint32_t start = base + item.pixelStart[j];
      m.pixelPathStart[item.pixels[j]] = start;
      m.pixelPathCount[item.pixels[j]] = item.pixelCount[j];
      m.pixelPath[item.pixels[j]] = item.vertices.data() + item.pixelStart[j];
      std::fill_n(m.pathStart.begin() + static_cast<std::ptrdiff_t>(start), item.pixelCount[j], start);
    }
  });
  m.lightSubpaths = lightSubpathsPerPass(film_.pixelCount());
  m.index(mergeRadius(firstMergeRadius(settings_) * scene_.bounds().radius, settings_.mergeRadiusAlpha, pass),
          mergeNonCaustic(settings_), mixBits(settings_.seed ^ mixBits(pass ^ 0xA0761D6478BD642Full)));
  // Each stored path's MIS partial sums and each mergeable vertex's terms, now that eta is known.
  bidirTracer_->prepareMergePass(m);
}

bool RenderSession::renderPass(const std::atomic<bool>* cancel) {
  tbb::enumerable_thread_specific<Counters> local;
  pixelsDone_.store(0, std::memory_order_relaxed);
  const uint64_t pass = schedule_.pass(passes_.load(std::memory_order_relaxed));
  if (metropolis_) {
    // Metropolis: the pass is the chains' next pixelCount mutations (the first pass bootstraps).
    Counters passCounters;
    if (!metropolis_->renderPass(film_.pixelCount(), film_, passCounters, cancel)) return false;
    counters_ += passCounters;
    pixelsDone_.store(film_.pixelCount(), std::memory_order_relaxed);
    passes_.fetch_add(1, std::memory_order_relaxed);
    return true;
  }
  // The merge pass's cost, for the counters' table: wall time times the threads (the workers
  // that wait between its parallel phases have nothing else to do), counted once the pass's
  // timed share is known.
  const bool merging = bidirTracer_ && bidirTracer_->merges();
  const bool timeMergePass = merging && bidirTracer_->timing();
  const uint64_t mergeStart = timeMergePass ? ticks() : 0;
  if (merging) traceMergePass(pass, local.local());
  const uint64_t mergeNanoseconds =
      timeMergePass ? elapsedNanoseconds(mergeStart, ticks()) * static_cast<uint64_t>(activeThreads()) : 0;
  // Item i records its splats in buffer i % inFlight: the items in flight are consecutive (they
  // enter and leave the pipeline in order), so no two share a buffer.
  const size_t threads = static_cast<size_t>(std::max(tbb::this_task_arena::max_concurrency(), 1));
  const size_t inFlight = std::max(kMinItemsInFlight, kItemsInFlightPerThread * threads);
  if (bidirTracer_ && tileSplats_.size() < inFlight)
    tileSplats_.resize(inFlight, SplatBuffer(settings_.width, settings_.height));
  if (varianceAware_ && factorSplats_.size() < inFlight) factorSplats_.resize(inFlight);
  // Variance-aware MIS: whether this pass's contributions go into the factors' sums.
  const bool learning = varianceAware_ && varianceAwareLearnsFrom(passes_.load(std::memory_order_relaxed));
  // --light-paths auto: whether this pass's contributions go into the second moments.
  if (lightPathChoice_ && lightPathSplats_.size() < inFlight) lightPathSplats_.resize(inFlight);
  const bool learningLightPaths = lightPathChoice_ && lightPathsLearnFrom(passes_.load(std::memory_order_relaxed));
  // --mis optimal learns from every pass (each contribution needs its balance weights anyway).
  if (optimal_ && optimalSplats_.size() < inFlight) optimalSplats_.resize(inFlight);
  const bool learningOptimal = optimal_ != nullptr;
  size_t next = 0;
  bool cancelled = false;  // both only touched by the pipeline's first stage, one item at a time
  tbb::parallel_pipeline(
      inFlight,
      tbb::make_filter<void, size_t>(tbb::filter_mode::serial_in_order,
                                     [&](tbb::flow_control& fc) {
                                       if (next < tiles_.size() && cancel && cancel->load(std::memory_order_relaxed))
                                         cancelled = true;
                                       if (cancelled || next == tiles_.size()) {
                                         fc.stop();
                                         return size_t{0};
                                       }
                                       return next++;
                                     }) &
          tbb::make_filter<size_t, size_t>(tbb::filter_mode::parallel,
                                           [&](size_t i) {
                                             SplatBuffer* splats = bidirTracer_ ? &tileSplats_[i % inFlight] : nullptr;
                                             renderTile(tiles_[i], pass, splats,
                                                        learning ? &factorSplats_[i % inFlight] : nullptr,
                                                        learningLightPaths ? &lightPathSplats_[i % inFlight] : nullptr,
                                                        optimal_ ? &optimalSplats_[i % inFlight] : nullptr,
                                                        learningOptimal, local.local());
                                             return i;
                                           }) &
          // The splats in the items' order (the path tracer has none: any order).
          tbb::make_filter<size_t, void>(bidirTracer_ ? tbb::filter_mode::serial_in_order : tbb::filter_mode::parallel,
                                         [&](size_t i) {
                                           if (bidirTracer_) tileSplats_[i % inFlight].addTo(splatSums_.get(), film_, pyramid_.get());
                                           if (learning) varianceAware_->addSplats(factorSplats_[i % inFlight]);
                                           if (learningLightPaths) lightPathChoice_->addSplats(lightPathSplats_[i % inFlight]);
                                           if (optimal_) optimal_->addSplats(optimalSplats_[i % inFlight], learningOptimal);
                                         }));
  Counters passCounters;
  for (const Counters& c : local) passCounters += c;
  if (passCounters.cameraSamples > 0)
    passCounters.mergePass.nanoseconds += static_cast<uint64_t>(
        static_cast<double>(mergeNanoseconds) * static_cast<double>(passCounters.timedSamples) /
        static_cast<double>(passCounters.cameraSamples));
  counters_ += passCounters;
  if (splatSums_) {
    if (cancelled) splatSums_->clear();
    else splatSums_->mergeInto(film_);
  }
  if (threadChecks_) {
    std::vector<TechniqueCheck::PassSums*> sums;
    for (TechniqueCheck::PassSums& t : threadChecks_->sums) sums.push_back(&t);
    if (cancelled) {
      for (TechniqueCheck::PassSums* t : sums) t->clear();
    } else {
      check_->finishPass(sums);
    }
  }
  if (pyramid_ && pyramid_->keepsMoments()) {
    // A pass's splats are scaled by P / its light subpaths in the film (Film::readout).
    if (cancelled) pyramid_->discardPass();
    else
      pyramid_->finishPass(static_cast<double>(film_.pixelCount()) /
                           static_cast<double>(lightSubpathsPerPass(film_.pixelCount())));
  }
  if (learning) {
    // The next pass weighs with factors that include this one (one camera sample a pixel).
    if (cancelled) {
      varianceAware_->discardPass();
      for (std::vector<VarianceAwareFactors::Splat>& list : factorSplats_) list.clear();
    } else {
      varianceAware_->finishPass(1.0);
    }
  }
  // A cancelled pass leaves part of its --light-paths auto sums: the session is discarded.
  if (lightPathChoice_ && cancelled)
    for (std::vector<LightPathChoice::Splat>& list : lightPathSplats_) list.clear();
  if (optimal_) {
    // The splats' corrections once every camera sample of the pass is in; then the coefficients
    // the next pass uses, from this one and those before (a cancelled pass's session is discarded).
    for (OptimalMis::Splats& list : optimalSplats_) list.clear();
    film_.addCorrections(optimal_->splatCorrections());
    if (cancelled) optimal_->discardPass();
    else optimal_->finishPass(learningOptimal);
  }
  if (cancelled) return false;
  film_.finishPass(1, bidirTracer_ ? lightSubpathsPerPass(film_.pixelCount()) : 0);
  const uint64_t done = passes_.fetch_add(1, std::memory_order_relaxed);
  if (lightPathChoice_) {
    // The pass's ray counts at its F into the cost model, its moments into the sums; after passes
    // 4, 8, 16, ... the next passes' F chosen anew (light_path_choice.h), from this session's
    // passes only (renderPass runs them in order: the choice is the same at any thread count).
    lightPathChoice_->countPass(passCounters);
    if (learningLightPaths) lightPathChoice_->finishPass();
    if (lightPathsChooseAfter(done)) {
      lightPathChoice_->choose(film_.readout());
      bidirTracer_->setLightPaths(lightPathChoice_->lightPaths());
    }
  }
  return true;
}

}  // namespace pathlab
