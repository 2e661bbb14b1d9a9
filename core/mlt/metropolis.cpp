// The chains: bootstrap, resampled starts, mutations with the expected-value splats.
#include "core/mlt/metropolis.h"

#include "core/film/splat_buffer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace pathlab {

const char* mltVariantName(MltVariant v) { return v == MltVariant::PrimarySpace ? "pss" : "mmlt"; }

std::optional<MltVariant> parseMltVariant(std::string_view name) {
  if (name == "mmlt") return MltVariant::Multiplexed;
  if (name == "pss") return MltVariant::PrimarySpace;
  return std::nullopt;
}

namespace {

// The chains' random streams, apart from the render's per-pixel ones (render_session.h): the
// bootstrap sample i's primary numbers, and chain c's own mutations and acceptances.
constexpr uint64_t kBootstrapSalt = 0x6a09e667f3bcc908ull, kChainSalt = 0xbb67ae8584caa73bull,
                   kAcceptSalt = 0x3c6ef372fe94f82bull, kStartSalt = 0xa54ff53a5f1d36f1ull,
                   kDirectCameraSalt = 0x510e527fade682d1ull, kDirectLightSalt = 0x9b05688c2b3e6c1full;
Pcg32 keyedStream(uint64_t seed, uint64_t index, uint64_t salt) {
  return Pcg32(mixBits(seed ^ salt ^ mixBits(index)), mixBits(index + salt));
}

// PSSMLT: a whole bidirectional sample's image contributions, wherever they land; its subpaths and
// records passed on to `forward` when it asks for them (with its demand).
class CollectingSink final : public SampleSink {
 public:
  struct Landed {
    Vec2 pRaster;
    Spectrum v;
  };
  explicit CollectingSink(SampleSink* forward = nullptr)
      : SampleSink(forward ? forward->demand() : SinkDemand{}), forward_(forward) {}
  std::vector<Landed> splats;  // the t = 1 contributions, where they land
  void beginSample(std::span<const PathVertex> camera, std::span<const PathVertex> light) override {
    if (forward_) forward_->beginSample(camera, light);
  }
  void walked(int nt, int ns) override {
    if (forward_) forward_->walked(nt, ns);
  }
  void record(const TechniqueResult& result) override {
    if (forward_) forward_->record(result);
  }

 protected:
  bool splat(Vec2 pRaster, const Spectrum& v) override {
    splats.push_back({pRaster, v});
    return true;
  }

 private:
  SampleSink* forward_;
};

// tracePath's sink: the subpaths walked and (MMLT: one technique) the path its record traced.
class PathSink final : public SampleSink {
 public:
  PathSink() : SampleSink(demand()) {}
  std::vector<Vec3> camera, light;  // the subpaths walked
  MltChainPath path;                // MMLT: the technique's path, when it formed one (`traced`)
  bool multiplexed = false;
  bool traced = false;
  void beginSample(std::span<const PathVertex> c, std::span<const PathVertex> l) override {
    camera.clear(), light.clear();
    for (const PathVertex& v : c) camera.push_back(v.p);
    for (const PathVertex& v : l) light.push_back(v.p);
  }
  void record(const TechniqueResult& r) override {
    if (!multiplexed || !r.traced || r.traced->size() < 2) return;
    // The technique's whole path, light end first: x_0 .. x_{s-1} from the light, x_k .. x_s
    // from the lens.
    const std::vector<Vec3>& p = r.traced->p;
    const auto s = static_cast<size_t>(std::clamp(r.s, 0, static_cast<int>(p.size())));
    path.light.assign(p.begin(), p.begin() + static_cast<std::ptrdiff_t>(s));
    path.camera.assign(p.rbegin(), p.rend() - static_cast<std::ptrdiff_t>(s));
    path.connected = s >= 1 && !path.camera.empty();
    traced = true;
  }

 protected:
  bool splat(Vec2, const Spectrum&) override { return true; }

 private:
  static SinkDemand demand() {
    SinkDemand d;
    d.everyTechnique = true;
    d.onPath = true;
    return d;
  }
};

}  // namespace

struct Metropolis::State {
  struct Contribution {
    Vec2 pRaster;
    Spectrum L;
  };
  std::vector<Contribution> contributions;  // MMLT: at most one
  float f = 0.f;                            // the target: the sum of their luminances
  Technique technique;                      // MMLT: the technique that sampled it
};

struct Metropolis::Chain {
  Chain(PrimarySamples s, Pcg32 accept, int k, int width, int height)
      : samples(std::move(s)), acceptRng(accept), length(k), splats(width, height) {}
  size_t index = 0;  // over every rank's chains
  // Watched (setWatchedChains): its index, and its path and last moves after the last pass.
  std::optional<MltWatchedChain> watch;
  PrimarySamples samples;
  Pcg32 acceptRng;
  int length = 0;  // MMLT: the chain's path length; PSSMLT: 0
  State current, proposal;
  double currentWeight = 0.0;  // the current state's expected-value weight not yet splatted
  SplatBuffer splats;          // this pass's (F / f with their weights)
  double largeSum = 0.0, largeSum2 = 0.0;  // this pass's large steps' f (b_k's refinement)
  uint64_t largeCount = 0;
  // This pass's proposals and acceptances: all, large steps, and (MMLT) by technique of the
  // chain's length, indexed by s.
  uint64_t proposed = 0, accepted = 0, largeProposed = 0, largeAccepted = 0;
  std::vector<uint64_t> proposedByS, acceptedByS;
};

Metropolis::Metropolis(const BidirTracer& tracer, int width, int height, int maxLength, uint64_t seed,
                       const MltOptions& options, const BidirTracer* direct, MltRanks ranks)
    : tracer_(tracer), width_(width), height_(height), maxLength_(maxLength), seed_(seed), options_(options),
      ranks_(ranks), direct_(direct) {
  if (ranks.count < 1 || ranks.rank < 0 || ranks.rank >= ranks.count)
    throw std::invalid_argument("a Metropolis rank must be one of its job's ranks");
  if (tracer.merges() || (direct && direct->merges()))
    throw std::invalid_argument("Metropolis light transport runs over connections only, not merges");
  if (direct_) directSum_.assign(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.0);
  enabledByLength_.resize(static_cast<size_t>(maxLength) + 1);
  for (const Technique x : techniquesUpTo(maxLength))
    if (tracer.techniques().contains(x)) enabledByLength_[static_cast<size_t>(x.length())].push_back(x);
  stats_.proposedByLength.assign(static_cast<size_t>(maxLength) + 1, 0);
  stats_.acceptedByLength.assign(static_cast<size_t>(maxLength) + 1, 0);
  if (options.variant == MltVariant::Multiplexed) {
    stats_.proposedByTechnique.assign(Technique::countUpTo(maxLength), 0);
    stats_.acceptedByTechnique.assign(Technique::countUpTo(maxLength), 0);
  }
  // A histogram for every length that will have chains (MMLT: each with an enabled technique;
  // PSSMLT: the one, if any technique is the chains'), made now so that every rank's sums() have
  // the same shape before the first pass.
  const bool multiplexed = options.variant == MltVariant::Multiplexed;
  totals_.assign(multiplexed ? static_cast<size_t>(maxLength) + 1 : 1, LengthTotals{});
  const size_t values = 3 * static_cast<size_t>(width) * static_cast<size_t>(height);
  const bool anyChains =
      std::any_of(enabledByLength_.begin(), enabledByLength_.end(), [](const auto& x) { return !x.empty(); });
  for (size_t k = 0; k < totals_.size(); ++k)
    if (multiplexed ? !enabledByLength_[k].empty() : anyChains) totals_[k].histogram.assign(values, 0.0);
}

Metropolis::~Metropolis() = default;

void Metropolis::evaluate(int length, PrimarySamples& samples, State& out, Counters& counters,
                          SampleSink* records) const {
  out.contributions.clear();
  out.f = 0.f;
  PrimarySampleStream camera(samples, 0), light(samples, 1);
  const Vec2 size(static_cast<float>(width_), static_cast<float>(height_));
  if (options_.variant == MltVariant::Multiplexed) {
    const std::vector<Technique>& techniques = enabledByLength_[static_cast<size_t>(length)];
    const auto n = static_cast<int>(techniques.size());
    // A length without techniques (left to BPT by --mlt-direct, or switched off) traces nothing:
    // its bootstrap samples are not samples.
    if (n == 0) return;
    ++counters.cameraSamples;
    const int j = std::min(static_cast<int>(camera.next1D() * static_cast<float>(n)), n - 1);
    const Technique x = techniques[static_cast<size_t>(j)];
    out.technique = x;
    const Vec2 pRaster = camera.next2D() * size;
    const Vec2 uLens = camera.next2D();
    PrimarySampleStream connection(samples, 2);
    const BidirTracer::TechniqueSample ts =
        tracer_.sampleTechnique(x.s, x.t, pRaster, uLens, camera, light, connection, counters, records);
    const Spectrum L = ts.L * static_cast<float>(n);
    const float f = luminance(L);
    if (f > 0.f && std::isfinite(f)) {
      out.contributions.push_back({ts.pRaster, L});
      out.f = f;
    }
    return;
  }
  ++counters.cameraSamples;
  const Vec2 pRaster = camera.next2D() * size;
  const Vec2 uLens = camera.next2D();
  CollectingSink sink(records);
  tracer_.sample(pRaster, uLens, camera, light, sink, counters);
  double f = 0.0;
  auto add = [&](Vec2 p, const Spectrum& L) {
    const float y = luminance(L);
    if (!(y > 0.f)) return;
    out.contributions.push_back({p, L});
    f += y;
  };
  add(pRaster, sink.cameraEstimate());
  for (const CollectingSink::Landed& s : sink.splats) add(s.pRaster, s.v);
  out.f = std::isfinite(f) ? static_cast<float>(f) : 0.f;
  if (!(out.f > 0.f)) out.contributions.clear();
}

bool Metropolis::bootstrap(Counters& counters, const std::atomic<bool>* cancel) {
  const bool multiplexed = options_.variant == MltVariant::Multiplexed;
  const uint64_t lengths = multiplexed ? static_cast<uint64_t>(maxLength_) : 1;
  const uint64_t total = options_.bootstrap * lengths;
  // Sample i has length i % lengths + 1 (MMLT; PSSMLT: 0) and is the (i / lengths)-th of it.
  auto lengthOf = [&](uint64_t i) { return multiplexed ? static_cast<int>(i % lengths) + 1 : 0; };
  auto bootstrapSamples = [&](uint64_t i) {
    return PrimarySamples(keyedStream(seed_, i, kBootstrapSalt), options_.sigma, options_.largeStep);
  };
  // Every enabled technique rendered by the direct tracer (MltOptions::directLength): no chains.
  if (std::all_of(enabledByLength_.begin(), enabledByLength_.end(), [](const auto& x) { return x.empty(); })) {
    bootstrapped_ = true;
    return true;
  }
  if (ranks_.count > 1 && !shareBootstrap_)
    throw std::logic_error("Metropolis over ranks needs the exchange of their bootstrap weights");
  const auto rankCount = static_cast<uint64_t>(ranks_.count), rank = static_cast<uint64_t>(ranks_.rank);
  std::vector<double> weights(total, 0.0);
  tbb::enumerable_thread_specific<Counters> local;
  std::atomic<bool> cancelled{false};
  tbb::parallel_for(tbb::blocked_range<uint64_t>(0, total, 1024), [&](const tbb::blocked_range<uint64_t>& r) {
    if (cancelled.load(std::memory_order_relaxed)) return;
    if (cancel && cancel->load(std::memory_order_relaxed)) {
      cancelled = true;
      return;
    }
    State state;
    Counters& c = local.local();
    for (uint64_t i = r.begin(); i != r.end(); ++i) {
      if (i % rankCount != rank) continue;  // another rank's sample (zero until the exchange)
      PrimarySamples samples = bootstrapSamples(i);
      evaluate(lengthOf(i), samples, state, c);
      weights[i] = state.f;
    }
  });
  for (const Counters& c : local) counters += c;
  if (cancelled) return false;
  // Every rank's samples on every rank: adding zeros changes no weight's bits, so each rank then
  // holds exactly the weights one process computes.
  if (ranks_.count > 1) shareBootstrap_(weights);

  // Each length's b_k from its samples (sums in index order: the same bits at any thread count).
  for (uint64_t i = 0; i < total; ++i) {
    LengthTotals& t = totals_[static_cast<size_t>(lengthOf(i))];
    t.bootSum += weights[i], t.bootSum2 += weights[i] * weights[i], ++t.bootCount;
  }
  updateNormalisation();
  bootstrapped_ = true;

  // Chains per length in proportion to b_k, at least one for every length with an enabled
  // technique (a length without a chain would be missing from the image; one whose bootstrap
  // found nothing starts from a zero sample, accepts every proposal until it finds light, and its
  // large steps estimate b_k), each started from a bootstrap sample of its length drawn in
  // proportion to f. No more chains than a pass has mutations (one per pixel), so that every chain
  // moves every pass.
  auto hasTechniques = [&](size_t k) { return !multiplexed || !enabledByLength_[k].empty(); };
  int lengthsInUse = 0;
  for (size_t k = 0; k < totals_.size(); ++k) lengthsInUse += hasTechniques(k) && (multiplexed ? k >= 1 : true);
  const int pixels = static_cast<int>(std::min<int64_t>(int64_t{width_} * height_, options_.chains));
  const int C = std::max(pixels, lengthsInUse);
  struct Start {
    size_t length;
    uint64_t sample;
  };
  std::vector<Start> starts;
  for (size_t k = multiplexed ? 1 : 0; k < totals_.size(); ++k) {
    if (!hasTechniques(k)) continue;
    const int64_t n = b_ > 0.0 ? std::max<int64_t>(1, std::llround(C * totals_[k].b() / b_)) : 1;
    // The cumulative weights of this length's samples i = k - 1 + j lengths (PSSMLT: i = j).
    const uint64_t first = multiplexed ? k - 1 : 0;
    std::vector<double> cdf(options_.bootstrap + 1, 0.0);
    for (uint64_t j = 0; j < options_.bootstrap; ++j) cdf[j + 1] = cdf[j] + weights[first + j * lengths];
    for (int64_t c = 0; c < n; ++c) {
      Pcg32 start = keyedStream(seed_, starts.size(), kStartSalt);
      // A uniform double from two draws: a float's 24 bits could not reach every one of millions
      // of bootstrap samples.
      const double u =
          (static_cast<double>(start.nextU32()) + static_cast<double>(start.nextU32()) * 0x1p-32) * 0x1p-32;
      uint64_t j = static_cast<uint64_t>(std::upper_bound(cdf.begin() + 1, cdf.end(), u * cdf.back()) - cdf.begin()) - 1;
      j = std::min(j, options_.bootstrap - 1);
      while (weights[first + j * lengths] <= 0.0 && j > 0) --j;  // no zero-weight start where b_k > 0
      starts.push_back({k, first + j * lengths});
    }
  }
  // Every rank knows every chain; chain c is rank c mod ranks' (consecutive chains share a length:
  // interleaved, the ranks get the lengths alike).
  chainLengths_.clear();
  for (const Start& start : starts) chainLengths_.push_back(static_cast<int>(start.length));
  std::vector<size_t> own;
  for (size_t c = rank; c < starts.size(); c += rankCount) own.push_back(c);
  chains_.resize(own.size());
  tbb::enumerable_thread_specific<Counters> startCounters;
  tbb::parallel_for(size_t{0}, own.size(), [&](size_t i) {
    const size_t c = own[i];
    // The bootstrap sample again (the same primary numbers, hence the same path), then a stream
    // of the chain's own for its mutations, so chains that start from one sample part at once.
    auto chain = std::make_unique<Chain>(bootstrapSamples(starts[c].sample), keyedStream(seed_, c, kAcceptSalt),
                                         static_cast<int>(starts[c].length), width_, height_);
    chain->index = c;
    evaluate(chain->length, chain->samples, chain->current, startCounters.local());
    chain->samples.reseed(keyedStream(seed_, c, kChainSalt));
    chains_[i] = std::move(chain);
  });
  for (const Counters& c : startCounters) counters += c;
  return true;
}

void Metropolis::updateNormalisation() {
  // b is a sum over lengths of independent means: its variance is the sum of theirs.
  double b = 0.0, variance = 0.0;
  for (const LengthTotals& t : totals_) {
    if (t.count() == 0) continue;
    const auto n = static_cast<double>(t.count());
    const double mean = t.b();
    b += mean;
    if (n > 1) variance += std::max(0.0, (t.bootSum2 + t.fSum2) / n - mean * mean) / (n - 1);
  }
  b_ = b;
  bError_ = std::sqrt(variance);
}

void Metropolis::runChain(Chain& chain, uint64_t mutations, Counters& counters) const {
  const bool multiplexed = options_.variant == MltVariant::Multiplexed;
  if (multiplexed && chain.proposedByS.empty()) {
    chain.proposedByS.assign(static_cast<size_t>(chain.length) + 1, 0);
    chain.acceptedByS.assign(static_cast<size_t>(chain.length) + 1, 0);
  }
  // F / f with its expected-value weight: the length's normalisation comes at read-out.
  auto splat = [&](const State& state, double weight) {
    if (!(weight > 0.0) || !(state.f > 0.f)) return;
    const auto scale = static_cast<float>(weight / static_cast<double>(state.f));
    for (const State::Contribution& c : state.contributions) chain.splats.splat(c.pRaster, c.L * scale);
  };
  // A watched chain replays its state before its last kMltWatchTrail proposals, then each of them.
  const uint64_t watchFrom = mutations > kMltWatchTrail ? mutations - kMltWatchTrail : 0;
  if (chain.watch) chain.watch->moves.clear();
  for (uint64_t m = 0; m < mutations; ++m) {
    if (chain.watch && m == watchFrom) chain.watch->current = tracePath(chain.length, chain.samples);
    chain.samples.startIteration();
    evaluate(chain.length, chain.samples, chain.proposal, counters);
    const bool large = chain.samples.largeStep();
    std::optional<MltChainPath> watched;
    if (chain.watch && m >= watchFrom) watched = tracePath(chain.length, chain.samples);
    if (large) {
      // An independent sample of f_k: b_k's estimate grows with it (Kelemen et al. 2002).
      const auto f = static_cast<double>(chain.proposal.f);
      chain.largeSum += f, chain.largeSum2 += f * f, ++chain.largeCount;
    }
    // Both mutations are symmetric (primary_samples.h): the acceptance is the targets' ratio.
    const double a = chain.current.f > 0.f
                         ? std::min(1.0, static_cast<double>(chain.proposal.f) / static_cast<double>(chain.current.f))
                         : 1.0;
    splat(chain.proposal, a);
    chain.currentWeight += 1.0 - a;
    ++chain.proposed, chain.largeProposed += large;
    const auto s = static_cast<size_t>(chain.proposal.technique.s);
    if (multiplexed) ++chain.proposedByS[s];
    const bool accepted = chain.acceptRng.next1D() < a;
    if (watched) {
      if (accepted) chain.watch->current = *watched;
      chain.watch->moves.push_back({std::move(*watched), accepted, large, chain.proposal.f});
    }
    if (accepted) {
      splat(chain.current, chain.currentWeight);
      std::swap(chain.current, chain.proposal);
      chain.currentWeight = 0.0;
      chain.samples.accept();
      ++chain.accepted, chain.largeAccepted += large;
      if (multiplexed) ++chain.acceptedByS[s];
    } else {
      chain.samples.reject();
    }
  }
  if (chain.watch) chain.watch->chainF = chain.current.f;
  // The pass's image is complete: the current state's weight so far goes in now.
  splat(chain.current, chain.currentWeight);
  chain.currentWeight = 0.0;
}

bool Metropolis::renderDirect(uint64_t pass, Counters& counters, const std::atomic<bool>* cancel) {
  const auto P = static_cast<uint64_t>(width_) * static_cast<uint64_t>(height_);
  // A row's light-tracing splats, added in row order after the rows ran (the same sums at any
  // thread count); each pixel's own estimate is its row's alone.
  std::vector<std::vector<CollectingSink::Landed>> rowSplats(static_cast<size_t>(height_));
  tbb::enumerable_thread_specific<Counters> local;
  std::atomic<bool> cancelled{false};
  tbb::parallel_for(tbb::blocked_range<int>(0, height_, 1), [&](const tbb::blocked_range<int>& r) {
    Counters& c = local.local();
    for (int y = r.begin(); y != r.end(); ++y) {
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        cancelled = true;
        return;
      }
      for (int x = 0; x < width_; ++x) {
        const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(width_) + static_cast<uint64_t>(x);
        Pcg32 rng = keyedStream(seed_, pass * P + pixel, kDirectCameraSalt);
        Pcg32 lightRng = keyedStream(seed_, pass * P + pixel, kDirectLightSalt);
        const Vec2 pRaster = Vec2(static_cast<float>(x), static_cast<float>(y)) + rng.next2D();  // box filter
        const Vec2 uLens = rng.next2D();
        ++c.cameraSamples;
        CollectingSink sink;
        direct_->sample(pRaster, uLens, rng, lightRng, sink, c);
        const Spectrum L = sink.cameraEstimate();
        if (isValidContribution(L))
          for (size_t i = 0; i < 3; ++i) directSum_[3 * pixel + i] += static_cast<double>(L[static_cast<int>(i)]);
        std::vector<CollectingSink::Landed>& row = rowSplats[static_cast<size_t>(y)];
        row.insert(row.end(), sink.splats.begin(), sink.splats.end());
      }
    }
  });
  for (const Counters& c : local) counters += c;
  if (cancelled) return false;  // the session is discarded
  for (const std::vector<CollectingSink::Landed>& row : rowSplats)
    for (const CollectingSink::Landed& s : row) {
      const std::optional<size_t> pixel = filmPixel(s.pRaster, width_, height_);
      if (!pixel || !isValidContribution(s.v)) continue;
      // One light subpath a pixel: a splat's share of the pixel is v P / (P light subpaths).
      for (size_t i = 0; i < 3; ++i) directSum_[3 * *pixel + i] += static_cast<double>(s.v[static_cast<int>(i)]);
    }
  ++directPasses_;
  return true;
}

bool Metropolis::renderPass(uint64_t mutations, Film& film, Counters& counters, const std::atomic<bool>* cancel) {
  if (!bootstrapped_ && !bootstrap(counters, cancel)) return false;
  const uint64_t passIndex = passes_;
  // The direct image's pass p is rank p mod ranks' (one process: every pass's).
  if (direct_ && passIndex % static_cast<uint64_t>(ranks_.count) == static_cast<uint64_t>(ranks_.rank) &&
      !renderDirect(passIndex, counters, cancel))
    return false;
  ++passes_;
  if (!chains_.empty()) {
    // Chain c of all C runs mutations / C of them, the remainder one more each to the chains from
    // an offset that moves every pass (this rank runs its chains' share).
    const uint64_t C = chainLengths_.size();
    mutations = std::max<uint64_t>(mutations, C);  // every chain moves (a 1 x 1 image has more chains)
    const uint64_t share = mutations / C, extra = mutations % C;
    const uint64_t offset = (passIndex * extra) % C;
    auto mutationsOf = [&](size_t own) {
      const uint64_t c = chains_[own]->index;
      return share + ((c + C - offset) % C < extra ? 1 : 0);
    };
    // The watched chains: n spread evenly over all chains, the middle one of each n-th (those of
    // this rank's).
    const size_t watching = std::min(static_cast<size_t>(watchCount_), static_cast<size_t>(C));
    for (size_t c = 0; c < chains_.size(); ++c) chains_[c]->watch.reset();
    const auto rankCount = static_cast<size_t>(ranks_.count), rank = static_cast<size_t>(ranks_.rank);
    for (size_t i = 0; i < watching; ++i) {
      const size_t c = (2 * i + 1) * static_cast<size_t>(C) / (2 * watching);
      if (c % rankCount != rank) continue;
      Chain& chain = *chains_[c / rankCount];
      chain.watch.emplace();
      chain.watch->chain = static_cast<int>(c);
      chain.watch->length = chain.length;
    }
    tbb::enumerable_thread_specific<Counters> local;
    std::atomic<bool> cancelled{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, chains_.size(), 1), [&](const tbb::blocked_range<size_t>& r) {
      for (size_t c = r.begin(); c != r.end(); ++c) {
        if (cancel && cancel->load(std::memory_order_relaxed)) {
          cancelled = true;
          return;
        }
        runChain(*chains_[c], mutationsOf(c), local.local());
      }
    });
    for (const Counters& c : local) counters += c;
    if (cancelled) return false;  // the session is discarded
    // The chains' splats, large steps and statistics, in chain order.
    MltStats& stats = stats_;
    for (size_t c = 0; c < chains_.size(); ++c) {
      Chain& chain = *chains_[c];
      LengthTotals& t = totals_[static_cast<size_t>(chain.length)];
      for (const Splat& s : chain.splats.imageSplats())
        for (size_t i = 0; i < 3; ++i) t.histogram[3 * size_t{s.pixel} + i] += static_cast<double>(s.v[static_cast<int>(i)]);
      chain.splats.clear();
      t.mutations += mutationsOf(c);
      t.fSum += chain.largeSum, t.fSum2 += chain.largeSum2, t.fCount += chain.largeCount;
      chain.largeSum = chain.largeSum2 = 0.0, chain.largeCount = 0;
      const auto k = static_cast<size_t>(chain.length);
      stats.proposed += chain.proposed, stats.accepted += chain.accepted;
      stats.largeProposed += chain.largeProposed, stats.largeAccepted += chain.largeAccepted;
      stats.proposedByLength[k] += chain.proposed, stats.acceptedByLength[k] += chain.accepted;
      chain.proposed = chain.accepted = chain.largeProposed = chain.largeAccepted = 0;
      for (size_t s = 0; s < chain.proposedByS.size(); ++s) {
        const size_t x = Technique{static_cast<int>(s), static_cast<int>(k + 1 - s)}.index();
        stats.proposedByTechnique[x] += chain.proposedByS[s], stats.acceptedByTechnique[x] += chain.acceptedByS[s];
        chain.proposedByS[s] = chain.acceptedByS[s] = 0;
      }
    }
    updateNormalisation();
  }
  writeImage(film);
  return true;
}

void Metropolis::writeImage(Film& film) const {
  // The image sum_k b_k P H_k / M_k as the film's splat sums over P light subpaths (a pixel reads
  // splat sum x P / P): rewritten whole, since every b_k moved.
  film.clear();
  std::span<double> image = film.sums()[1];
  const auto P = static_cast<double>(film.pixelCount());
  if (directPasses_ > 0) {
    const double scale = 1.0 / static_cast<double>(directPasses_);
    for (size_t i = 0; i < image.size(); ++i) image[i] = scale * directSum_[i];
  }
  for (const LengthTotals& t : totals_) {
    if (t.mutations == 0 || t.histogram.empty()) continue;
    const double scale = t.b() * P / static_cast<double>(t.mutations);
    for (size_t i = 0; i < image.size(); ++i) image[i] += scale * t.histogram[i];
  }
  film.finishPass(0, film.pixelCount());
}

std::vector<std::span<double>> Metropolis::sums() {
  // The counts as doubles (exact below 2^53): per length M_k and the large steps' sums, the direct
  // passes, then the statistics.
  packed_.clear();
  for (const LengthTotals& t : totals_)
    packed_.insert(packed_.end(), {static_cast<double>(t.mutations), t.fSum, t.fSum2, static_cast<double>(t.fCount)});
  packed_.push_back(static_cast<double>(directPasses_));
  for (const uint64_t x : {stats_.proposed, stats_.accepted, stats_.largeProposed, stats_.largeAccepted})
    packed_.push_back(static_cast<double>(x));
  for (const std::vector<uint64_t>* v : {&stats_.proposedByLength, &stats_.acceptedByLength,
                                         &stats_.proposedByTechnique, &stats_.acceptedByTechnique})
    for (const uint64_t x : *v) packed_.push_back(static_cast<double>(x));
  std::vector<std::span<double>> all;
  for (LengthTotals& t : totals_)
    if (!t.histogram.empty()) all.emplace_back(t.histogram);
  if (!directSum_.empty()) all.emplace_back(directSum_);
  all.emplace_back(packed_);
  return all;
}

void Metropolis::sumsCombined() {
  size_t i = 0;
  auto next = [&] { return packed_.at(i++); };
  auto count = [&] { return static_cast<uint64_t>(next()); };
  for (LengthTotals& t : totals_) {
    t.mutations = count();
    t.fSum = next(), t.fSum2 = next();
    t.fCount = count();
  }
  directPasses_ = count();
  stats_.proposed = count(), stats_.accepted = count(), stats_.largeProposed = count(), stats_.largeAccepted = count();
  for (std::vector<uint64_t>* v : {&stats_.proposedByLength, &stats_.acceptedByLength, &stats_.proposedByTechnique,
                                   &stats_.acceptedByTechnique})
    for (uint64_t& x : *v) x = count();
  updateNormalisation();
}

std::vector<float> Metropolis::chainDensity() const {
  // H_k holds F / f times the weights, so its luminance is the weight times lum(F) / f: the
  // share of the state's weight its contribution to this pixel carries (all of it in MMLT).
  uint64_t mutations = 0;
  for (const LengthTotals& t : totals_) mutations += t.histogram.empty() ? 0 : t.mutations;
  if (mutations == 0) return {};
  const size_t P = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  std::vector<double> sum(P, 0.0);
  for (const LengthTotals& t : totals_) {
    if (t.histogram.empty() || t.mutations == 0) continue;
    for (size_t p = 0; p < P; ++p)
      // luminance()'s weights, in double.
      sum[p] += 0.2126 * t.histogram[3 * p] + 0.7152 * t.histogram[3 * p + 1] + 0.0722 * t.histogram[3 * p + 2];
  }
  std::vector<float> density(P);
  const double scale = static_cast<double>(P) / static_cast<double>(mutations);
  for (size_t p = 0; p < P; ++p) density[p] = static_cast<float>(scale * sum[p]);
  return density;
}

MltChainPath Metropolis::tracePath(int length, PrimarySamples samples) const {
  // The numbers the state's path read are up to date at this iteration, so reading them again
  // mutates nothing: the copy makes the same path (a coordinate it did not read would be drawn
  // from the copy's stream, never the chain's).
  PathSink sink;
  sink.multiplexed = options_.variant == MltVariant::Multiplexed;
  State state;
  Counters scratch;  // a replay is no sample of the render
  evaluate(length, samples, state, scratch, &sink);
  MltChainPath path = sink.traced ? std::move(sink.path) : MltChainPath{};
  if (!sink.traced) path.light = std::move(sink.light), path.camera = std::move(sink.camera);
  path.technique = state.technique;
  path.f = state.f;
  return path;
}

std::vector<MltWatchedChain> Metropolis::watched() const {
  std::vector<MltWatchedChain> w;
  for (const std::unique_ptr<Chain>& chain : chains_)
    if (chain->watch) w.push_back(*chain->watch);
  return w;
}

MltChainState Metropolis::replayChain(size_t c, SampleSink* records) const {
  const auto rankCount = static_cast<size_t>(ranks_.count);
  if (c >= chainLengths_.size() || c % rankCount != static_cast<size_t>(ranks_.rank))
    throw std::out_of_range("no such Metropolis chain on this rank");
  const Chain& chain = *chains_[c / rankCount];
  MltChainState out;
  out.chain = static_cast<int>(c);
  out.length = chain.length;
  PrimarySamples samples = chain.samples;  // as tracePath: its numbers are up to date
  std::vector<std::pair<size_t, float>> reads;
  samples.logReads(&reads);
  State state;
  Counters scratch;
  evaluate(chain.length, samples, state, scratch, records);
  for (const auto& [index, value] : reads) {
    std::vector<float>& stream = out.numbers[index % PrimarySamples::kStreams];
    const size_t i = index / PrimarySamples::kStreams;
    if (stream.size() <= i) stream.resize(i + 1, 0.f);
    stream[i] = value;
  }
  out.technique = state.technique;
  out.f = state.f;
  for (const State::Contribution& x : state.contributions) out.contributions.push_back({x.pRaster, x.L});
  return out;
}

std::vector<int> Metropolis::chainsByLength() const {
  std::vector<int> n(std::max(static_cast<size_t>(maxLength_) + 1, totals_.size()), 0);
  for (const int k : chainLengths_) ++n[static_cast<size_t>(k)];
  return n;
}

}  // namespace pathlab
