// Where one bidirectional sample's technique results go: the camera estimate of its pixel, the
// t = 1 splats on the film, the technique pyramid, a replay trace, and the counters. The kernel
// (bidir_tracer.h) evaluates techniques; new outputs are added here without touching it (and say
// so in imageOnly(), which lets the kernel skip the result record when only the image needs it).
#pragma once

#include "core/bpt/technique_result.h"
#include "core/check/technique_check.h"
#include "core/film/film.h"
#include "core/film/splat_buffer.h"
#include "core/film/technique_films.h"
#include "core/counters/counters.h"

namespace pathlab {

// The outputs a sample feeds; each may be null.
struct SampleTargets {
  Film* film = nullptr;               // t = 1 splats of the image, atomically
  TechniqueFilms* pyramid = nullptr;  // every technique of the pyramid's lengths, weighted and unweighted
  SampleTrace* trace = nullptr;       // a record of every technique tried
  SampleId id;
  SplatBuffer* splats = nullptr;  // the work item's buffer of the t = 1 splats, instead of `film` and the pyramid's
  TechniqueCheck::PassSums* check = nullptr;  // the thread's sums of the consistency check
};

class SampleOutputs {
 public:
  SampleOutputs(const SampleTargets& targets, Counters& counters) : targets_(targets), counters_(counters) {}

  // Whether an output wants a technique's contribution even where its image weight is zero (the
  // pyramid's unweighted films, the replay trace): the kernel then still traces its shadow ray.
  bool wantsEveryContribution() const { return targets_.trace != nullptr || targets_.check != nullptr; }
  // Whether every result goes only to the image and the counters, for the techniques outside the
  // pyramid (which add() alone feeds): BidirTracer::runImageOnly may then evaluate them. A new
  // output that reads results must make this false.
  bool imageOnly() const { return targets_.trace == nullptr && targets_.check == nullptr; }
  // Whether an output needs TechniqueResult::onPath (the replay trace).
  bool wantsOnPath() const { return targets_.trace != nullptr; }
  // Whether an output needs TechniqueResult::densityRatios (the consistency check): O(n) a result.
  bool wantsDensityRatios() const { return targets_.check != nullptr; }
  // Whether an output needs TechniqueResult::sampleableBy: the consistency check, or a pyramid
  // kept for the technique maps (TechniqueFilms::keepsSampleable).
  bool wantsSampleable() const {
    return targets_.check != nullptr || (targets_.pyramid != nullptr && targets_.pyramid->keepsSampleable());
  }

  void add(const TechniqueResult& result, TechniqueCounters& counters);
  // add() of a contributed result of technique (s, t) with image weight `weight`, landing at
  // pRaster if t = 1, for a sample with no trace or check and a technique outside the pyramid
  // (BidirTracer::runImageOnly): the same counting, discarding, splat and pixel sum.
  void addToImage(int s, int t, Vec2 pRaster, const Spectrum& unweighted, float weight, TechniqueCounters& counters) {
    ++counters.contributed;
    if (!isValidContribution(unweighted)) {
      discard(unweighted, s, t, counters);
      return;
    }
    toImage(s, t, pRaster, unweighted * weight, counters);
  }
  // The sum of the t >= 2 contributions: the sample's estimate for its own pixel.
  const Spectrum& cameraEstimate() const { return cameraEstimate_; }

 private:
  void discard(const Spectrum& value, int s, int t, TechniqueCounters& counters);
  // A weighted contribution into the image: the sample's pixel, or a splat at pRaster (t = 1).
  void toImage(int s, int t, Vec2 pRaster, const Spectrum& contribution, TechniqueCounters& counters) {
    if (isBlack(contribution)) return;
    if (t == 1) {
      splat(s, t, pRaster, contribution, counters);
    } else {
      cameraEstimate_ += contribution;
    }
  }
  void splat(int s, int t, Vec2 pRaster, const Spectrum& contribution, TechniqueCounters& counters);
  void trace(const TechniqueResult& result);
  const SampleTargets& targets_;
  Counters& counters_;
  Spectrum cameraEstimate_{0.f};
};

}  // namespace pathlab
