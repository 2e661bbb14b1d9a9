// Metropolis light transport over pathlab's bidirectional techniques (issue 33; Veach and Guibas
// 1997; the course notes' "advanced, global path sampling technique").
//
// Markov chains explore primary sample space (core/sampling/primary_samples.h) in proportion to a
// scalar target f, the luminance of what the state contributes to the image:
//   - MltVariant::Multiplexed (MMLT, Hachisuka, Kaplanyan and Dachsbacher 2014, pbrt-v4's MLT): a
//     chain keeps one path length k; its first number picks one of the n_k enabled techniques
//     (s, t) of that length, the rest sample its two subpaths and connection. Its contribution is
//     n_k w_{s,t} f / p_{s,t}: the technique's MIS-weighted estimate times n_k, whose expectation
//     over the technique's choice is the MIS estimate of length k, so the technique set and the
//     heuristic shape the chain, and a disabled technique is never proposed;
//   - MltVariant::PrimarySpace (PSSMLT, Kelemen et al. 2002): the state is a whole bidirectional
//     sample (every enabled technique of every length, BidirTracer::sample) and f is the sum of
//     its contributions' luminances, wherever they land.
//
// The normalisation b = sum_k b_k, b_k = integral f_k du, is estimated from independent bootstrap
// samples. Each length gets chains in proportion to its b_k (at least one where b_k > 0), and each
// chain starts from one of its length's bootstrap samples chosen in proportion to f (resampling:
// the chains start in the stationary distribution, so there is no start-up bias to discard). Each
// mutation adds F / f of the proposal with weight a (its acceptance probability) and of the current
// state with 1 - a (Veach's expected-value trick; the current state's weight kept until it
// changes) to its length's histogram H_k, F the colour. A large step proposes an independent
// sample, so its f refines b_k as the chains run (Kelemen et al. 2002, sec. 4): b's error shrinks
// with the render instead of staying in the image. With M_k mutations of length k over P pixels a
// pixel is sum_k b_k P H_k / M_k (consistent: the ratio's bias falls as 1 / M_k).
#pragma once

#include "core/bpt/bidir_tracer.h"
#include "core/counters/counters.h"
#include "core/film/film.h"
#include "core/mlt/mlt_options.h"
#include "core/sampling/primary_samples.h"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

namespace pathlab {

// How the chains moved: proposals and acceptances, over all, by mutation kind, by path length and
// (MMLT) by technique (Technique::index()).
struct MltStats {
  uint64_t proposed = 0, accepted = 0;
  uint64_t largeProposed = 0, largeAccepted = 0;
  std::vector<uint64_t> proposedByLength, acceptedByLength;        // index k, 0 unused
  std::vector<uint64_t> proposedByTechnique, acceptedByTechnique;  // MMLT only
  double acceptance() const { return proposed ? static_cast<double>(accepted) / static_cast<double>(proposed) : 0.0; }
};

// A chain's state as the viewer's 3D view draws it (Metropolis::setWatchedChains): the vertices of
// its two subpaths, the light one from the emitter and the camera one from the lens. MMLT: the
// technique's path x_0 .. x_k split at s (light x_0 .. x_{s-1}, camera x_k .. x_s), `connected`
// by its connection edge x_{s-1} -- x_s when s >= 1 (for s = 1 with t >= 2 the light point is the
// one next-event estimation sampled); when no path was formed (a walk ended early, a delta
// vertex), what was walked. PSSMLT: the sample's two subpaths, which every enabled technique of
// the sample connects (no one edge is the connection).
struct MltChainPath {
  Technique technique;  // MMLT: the state's technique (PSSMLT: unused)
  float f = 0.f;        // the target (zero: a proposal that found nothing)
  std::vector<Vec3> light, camera;
  bool connected = false;
};
struct MltChainMove {
  MltChainPath proposal;
  bool accepted = false, large = false;
  float chainF = 0.f;  // the target the chain evaluated for the proposal (the replay's proposal.f is the same)
};
// Where a watched chain is and how it moved in the last pass.
struct MltWatchedChain {
  int chain = 0, length = 0;         // its index, and (MMLT) its path length
  MltChainPath current;              // its state after the pass
  float chainF = 0.f;                // the target the chain holds for it (current.f, the replay's, is the same)
  std::vector<MltChainMove> moves;   // the pass's last proposals, oldest first (at most kMltWatchTrail)
};
inline constexpr int kMaxMltWatchedChains = 16, kMltWatchTrail = 16;

// A chain's current state replayed (`pathlab inspect` on an MLT render): the primary numbers its
// path read, stream by stream in reading order (PrimarySamples::kStreams: camera, light,
// connection), the technique (MMLT), the target and what it adds to the image where.
struct MltChainState {
  int chain = 0, length = 0;
  Technique technique;
  float f = 0.f;
  std::vector<float> numbers[PrimarySamples::kStreams];
  struct Contribution {
    Vec2 pRaster;
    Spectrum L;
  };
  std::vector<Contribution> contributions;
};

// What a viewer shows of the chains after a pass (published with the image).
struct MltSummary {
  double b = 0.0, bError = 0.0;
  MltStats stats;
  std::vector<int> chainsByLength;
  int directLength = 0;        // MltOptions::directLength
  uint64_t directSamples = 0;  // per pixel, of the paths up to directLength edges
  // Where the chains spend their time (Metropolis::chainDensity), width x height, row-major.
  std::vector<float> density;
  int width = 0, height = 0;
  std::vector<MltWatchedChain> watched;  // Metropolis::setWatchedChains
};

// An MPI job's share of the work (RenderSession's PassSchedule: rank `first` of `stride`): the
// bootstrap samples i = rank (mod count) and the chains c = rank (mod count) are this rank's, and
// so is the direct image's pass p (MltOptions::directLength) when p = rank (mod count). The ranks'
// bootstrap weights are combined (Metropolis::setBootstrapExchange) so that every rank knows b and
// every chain's start; a pass runs this rank's chains' share of the job's mutations, exactly the
// mutations those chains run in one process, and the ranks' sums add up to one process's.
struct MltRanks {
  int rank = 0, count = 1;
};

class Metropolis {
 public:
  // `tracer` has no merges (validateSettings refuses mlt with them); width x height is the film's.
  // `direct` (or null): the tracer of the lengths up to MltOptions::directLength, which renders
  // one bidirectional sample a pixel each pass into an image added to the chains' (`tracer` then
  // leaves those lengths out).
  Metropolis(const BidirTracer& tracer, int width, int height, int maxLength, uint64_t seed, const MltOptions& options,
             const BidirTracer* direct = nullptr, MltRanks ranks = {});
  ~Metropolis();

  // The bootstrap (b and the chains' starting states), in parallel; the first pass runs it.
  // Returns false when cancelled (the session is then discarded).
  bool bootstrap(Counters& counters, const std::atomic<bool>* cancel = nullptr);
  bool bootstrapped() const { return bootstrapped_; }
  // One pass: `mutations` mutations shared among the chains, their splats added to their lengths'
  // histograms in chain order (the same seed gives the same image at any thread count), then the
  // image sum_k b_k P H_k / M_k written into `film` (its splat sums, normalised by P light
  // subpaths). Returns false when cancelled.
  bool renderPass(uint64_t mutations, Film& film, Counters& counters, const std::atomic<bool>* cancel = nullptr);

  // b: the integral of f over the chains' space (zero: nothing to render, the image stays black),
  // from the bootstrap and every large step so far, and its standard error from their spread.
  // The image's overall brightness is off by about b's relative error.
  double normalisation() const { return b_; }
  double normalisationError() const { return bError_; }
  const MltStats& stats() const { return stats_; }
  // Samples per pixel of the lengths rendered by BPT beside the chains (MltOptions::directLength).
  uint64_t directSamples() const { return directPasses_; }
  // The chains' share of each path length (MMLT; PSSMLT: all in length 0).
  std::vector<int> chainsByLength() const;
  // Where the chains spend their time: per pixel, the chains' expected-value weight that landed
  // there (each state's weight spread over its contributions in proportion to their luminance),
  // times P over all their mutations: 1 where they stay as long as in an average pixel. The
  // image's luminance from a length k is b_k times its chains' density, so with one length the
  // image is b times this (Veach 1997 sec. 11.3: the chain's stationary density is f / b).
  // Empty before the first pass and without chains.
  std::vector<float> chainDensity() const;
  MltSummary summary() const {
    return {b_,     bError_,         stats_, chainsByLength(), direct_ ? options_.directLength : 0, directPasses_,
            chainDensity(), width_, height_, watched()};
  }

  // Watch `n` chains (at most kMaxMltWatchedChains; 0: none, the default), spread evenly over the
  // chains (which are laid out length by length in proportion to b_k, so the lengths that matter
  // most are watched most): each pass then replays the last kMltWatchTrail proposals of each into
  // its path (a few dozen evaluations a pass; the image is the same bits). Not an estimator
  // option: set it between passes.
  void setWatchedChains(int n) { watchCount_ = std::clamp(n, 0, kMaxMltWatchedChains); }
  // The watched chains after the last pass (empty before the first, without chains or watching).
  std::vector<MltWatchedChain> watched() const;
  // Chains after the bootstrap, over every rank (0 before it).
  size_t chainCount() const { return chainLengths_.size(); }

  // With ranks: `exchange` sums the ranks' bootstrap weights in place (each rank's own samples, zero
  // elsewhere), collectively on every rank, during the first pass. Required when count > 1.
  void setBootstrapExchange(std::function<void(std::span<double>)> exchange) { shareBootstrap_ = std::move(exchange); }
  // Everything this rank accumulated, as flat arrays of doubles in an order fixed by the settings
  // (RenderSession::sums): the lengths' histograms, the direct image and the counts (mutations,
  // the large steps' sums, the statistics) packed as doubles when called. Adding another rank's
  // element by element, then sumsCombined(), gives the job's.
  std::vector<std::span<double>> sums();
  void sumsCombined();
  // The image sum_k b_k P H_k / M_k (and the direct lengths') written into `film` as its splat sums.
  void writeImage(Film& film) const;
  // Chain `c`'s current state (after the bootstrap; a chain of this rank's), replayed from its primary numbers: the same
  // path, target and contributions the chain holds. `records` (or null) gets the replayed
  // sample's subpaths and technique records, with the extras its demand asks for.
  MltChainState replayChain(size_t c, SampleSink* records = nullptr) const;

 private:
  struct State;
  struct Chain;
  // The state's contributions and f for the primary numbers `samples` (of a chain of this length);
  // `records` (or null) gets the sample's subpaths and technique records (replayChain, tracePath).
  void evaluate(int length, PrimarySamples& samples, State& out, Counters& counters,
                SampleSink* records = nullptr) const;
  // The path of the state whose numbers `samples` holds at its present iteration, replayed on a
  // copy (the chain's own numbers and random stream stay untouched).
  MltChainPath tracePath(int length, PrimarySamples samples) const;
  void runChain(Chain& chain, uint64_t mutations, Counters& counters) const;
  // One bidirectional sample a pixel of the direct lengths into directSum_; false when cancelled.
  bool renderDirect(uint64_t pass, Counters& counters, const std::atomic<bool>* cancel);

  const BidirTracer& tracer_;
  int width_, height_, maxLength_;
  uint64_t seed_;
  MltOptions options_;
  std::vector<std::vector<Technique>> enabledByLength_;  // MMLT: the techniques a chain of length k picks from
  std::vector<std::unique_ptr<Chain>> chains_;
  // Per length (MMLT: index k; PSSMLT: 0): the histogram H_k (3 doubles a pixel, made for a length
  // with enabled techniques, which gets at least one chain), its mutations M_k, and the sums of f
  // that estimate b_k: over the bootstrap samples (every rank's, the same on every rank) and over
  // this rank's chains' large steps.
  struct LengthTotals {
    std::vector<double> histogram;
    uint64_t mutations = 0;
    double bootSum = 0.0, bootSum2 = 0.0;
    uint64_t bootCount = 0;
    double fSum = 0.0, fSum2 = 0.0;
    uint64_t fCount = 0;
    uint64_t count() const { return bootCount + fCount; }
    double b() const { return count() ? (bootSum + fSum) / static_cast<double>(count()) : 0.0; }
  };
  std::vector<LengthTotals> totals_;
  void updateNormalisation();
  double b_ = 0.0, bError_ = 0.0;
  bool bootstrapped_ = false;
  MltStats stats_;
  uint64_t passes_ = 0;
  int watchCount_ = 0;
  MltRanks ranks_;
  std::function<void(std::span<double>)> shareBootstrap_;
  std::vector<int> chainLengths_;  // every rank's chains' lengths, by chain index (chains_: this rank's)
  std::vector<double> packed_;     // sums()' counts
  const BidirTracer* direct_ = nullptr;
  std::vector<double> directSum_;  // 3 a pixel: the direct samples' camera estimates and splats
  uint64_t directPasses_ = 0;
};

}  // namespace pathlab
