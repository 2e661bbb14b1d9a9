// Primary sample space (Kelemen, Szirmay-Kalos, Antal and Csonka 2002): a path is a deterministic
// function of a vector of uniform numbers u in [0,1)^n, and a Markov chain over u explores path
// space without knowing anything of paths. PrimarySamples is the chain's state u and its two
// mutations: the large step (every number drawn afresh: an independent sample) and the small step
// (every number perturbed by a normal of standard deviation sigma, wrapped into [0,1)). Both are
// symmetric, so the Metropolis acceptance is the ratio of the target alone (core/mlt/metropolis.h).
//
// The vector is lazy, as in pbrt-v4's MLTSampler: a number is mutated only when a path reads it,
// with every mutation it missed applied at once (k small steps are one of standard deviation
// sigma sqrt(k); a large step since its last read replaces it). A path that reads more numbers
// than the last one extends the vector; one that reads fewer leaves the rest unchanged, so the
// target is a function of u alone and the chain's stationary density is exact.
//
// The numbers are read through streams (PrimarySampleStream), interleaved so that the camera
// subpath's i-th number is the same coordinate whatever the light subpath read: a small step on a
// path whose light subpath grew longer moves its camera subpath only a little.
#pragma once

#include "core/math/rng.h"
#include "core/math/types.h"

#include <cstdint>
#include <utility>
#include <vector>

namespace pathlab {

class PrimarySamples {
 public:
  // The numbers of a path come from kStreams interleaved streams (camera, light, connection).
  static constexpr int kStreams = 3;

  // The chain's own random numbers (what to mutate, and how) come from `rng`.
  PrimarySamples(Pcg32 rng, float sigma, float largeStepProbability)
      : rng_(rng), sigma_(sigma), largeStepProbability_(largeStepProbability) {}

  // Starts a proposal: a large step with probability largeStepProbability, else a small one.
  // Its numbers change as the path reads them; accept() keeps them, reject() restores the state.
  void startIteration() {
    ++iteration_;
    largeStep_ = rng_.next1D() < largeStepProbability_;
  }
  void accept() {
    if (largeStep_) lastLargeStep_ = iteration_;
  }
  void reject();
  bool largeStep() const { return largeStep_; }
  // Replaces the chain's own random numbers (a chain started from a bootstrap sample continues on
  // a stream of its own, so two chains started from the same sample part at once).
  void reseed(Pcg32 rng) { rng_ = rng; }

  // The coordinate `index` of u, brought up to date with this iteration's mutation.
  float get(size_t index);
  // How many coordinates the chain has read so far.
  size_t size() const { return x_.size(); }
  // Every coordinate get() reads from now on, appended to *log as (index, value) (null: none):
  // the numbers a path was made from (`pathlab inspect` on a chain's state).
  void logReads(std::vector<std::pair<size_t, float>>* log) { readLog_ = log; }

 private:
  struct Coordinate {
    float value = 0.f, backup = 0.f;
    // The iteration that last set value (backup); -1: never, a coordinate no path read yet.
    int64_t modified = -1, backupModified = -1;
  };
  void mutate(Coordinate& x);

  Pcg32 rng_;
  float sigma_, largeStepProbability_;
  std::vector<Coordinate> x_;
  // Iteration 0 is the state's first sample, a large step: every coordinate drawn afresh.
  int64_t iteration_ = 0, lastLargeStep_ = 0;
  bool largeStep_ = true;
  std::vector<std::pair<size_t, float>>* readLog_ = nullptr;
};

// One stream of a PrimarySamples: the random-number interface the walks and connections draw from
// (next1D, next2D, nextU32, as Pcg32's), reading the coordinates stream, stream + kStreams, ...
class PrimarySampleStream {
 public:
  PrimarySampleStream(PrimarySamples& samples, int stream) : samples_(&samples), next_(static_cast<size_t>(stream)) {}
  float next1D() {
    const float u = samples_->get(next_);
    next_ += PrimarySamples::kStreams;
    return u;
  }
  Vec2 next2D() {
    const float a = next1D();
    return {a, next1D()};
  }
  // 32 bits from one coordinate (its 24 significant bits shifted up): a key that a small step
  // changes to an unrelated one.
  uint32_t nextU32() { return static_cast<uint32_t>(next1D() * 0x1p32f); }

 private:
  PrimarySamples* samples_;
  size_t next_;
};

}  // namespace pathlab
