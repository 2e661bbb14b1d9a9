// Work and health counters of a render: rays traced, samples the film refused, and per
// bidirectional technique (s, t) the connections tried, blocked and zero, the shadow rays traced,
// the time spent and the contributions discarded. Plain data: one copy per thread, merged after
// each pass.
#pragma once

#include "core/math/types.h"
#include "core/sampling/technique.h"

#include <array>
#include <cstdint>

namespace pathlab {

// Techniques of length <= kCountedLength get counters of their own; longer ones share a bucket.
inline constexpr int kCountedLength = 12;
inline constexpr size_t kCountedTechniques = Technique::countUpTo(kCountedLength);

struct DiscardCounts {
  uint64_t nan = 0, inf = 0, negative = 0;
  uint64_t total() const { return nan + inf + negative; }
  DiscardCounts& operator+=(const DiscardCounts& o) {
    nan += o.nan;
    inf += o.inf;
    negative += o.negative;
    return *this;
  }
};

struct TechniqueCounters {
  uint64_t tried = 0;        // connect(s, t) called with both prefixes present
  uint64_t zero = 0;         // no contribution before any visibility test (delta vertex, f = 0, ...), or an
                             // MIS weight of zero with nothing else using it (no shadow ray traced)
  uint64_t blocked = 0;      // the shadow ray was occluded
  uint64_t contributed = 0;  // a non-zero unweighted contribution
  DiscardCounts discarded;   // contributions refused as NaN, Inf or negative
  uint64_t shadowRays = 0;   // visibility queries of its connections (blocked + contributed for s >= 1)
  uint64_t walkRays = 0;     // closest-hit rays of its own subpaths (naive BPT, ConnectStrategy::Endpoints)
  // connect() and misWeight, summed over threads, of the timed samples only (BidirTracer::setTiming):
  // compare shares, or time per timed try, never totals.
  uint64_t nanoseconds = 0;
  TechniqueCounters& operator+=(const TechniqueCounters& o) {
    tried += o.tried;
    zero += o.zero;
    blocked += o.blocked;
    contributed += o.contributed;
    discarded += o.discarded;
    shadowRays += o.shadowRays;
    walkRays += o.walkRays;
    nanoseconds += o.nanoseconds;
    return *this;
  }
};

// Slot of a valid technique: lengths up to kCountedLength by Technique::index(), every longer
// technique in the last slot.
inline size_t techniqueSlot(Technique x) { return x.length() > kCountedLength ? kCountedTechniques : x.index(); }

// The random walks that build the subpaths: closest-hit rays always, time while timing is on.
struct WalkCounters {
  uint64_t rays = 0;
  uint64_t nanoseconds = 0;
  WalkCounters& operator+=(const WalkCounters& o) {
    rays += o.rays;
    nanoseconds += o.nanoseconds;
    return *this;
  }
};

// Which sample this is, for the discarded-sample report (Counters::discardExamples).
struct SampleId {
  int x = -1, y = -1;
  uint64_t sample = 0;
};

// Where a discarded contribution came from, so `pathlab render --replay X,Y,SAMPLE` can
// reproduce it. s = t = -1 for a whole path-tracer sample.
struct DiscardExample {
  int x = -1, y = -1;
  uint64_t sample = 0;
  int s = -1, t = -1;
  Spectrum value{0.f};
};
inline constexpr size_t kDiscardExamples = 4;

struct Counters {
  uint64_t cameraSamples = 0;
  uint64_t rays = 0;          // closest-hit queries
  uint64_t shadowRays = 0;    // visibility queries
  DiscardCounts discardedSamples;  // refused at the film's door (whole samples or splats)
  std::array<TechniqueCounters, kCountedTechniques + 1> techniques{};
  WalkCounters cameraWalk, lightWalk;  // bidirectional tracer only
  // Vertex merging (bidirectional tracer with merges): the pass's store of light subpaths (its
  // walks' rays; its time, wall time times threads, scaled to the pass's timed samples so that it
  // adds to theirs) and, on timed samples, the range searches at the camera vertices (their time
  // less the merges' own, which their techniques keep).
  WalkCounters mergePass, mergeSearch;
  uint64_t timedSamples = 0;           // camera samples timed (a fraction of them while timing is on)
  // Paths whose enabled techniques' MIS weights did not sum to one (RenderSettings::checkMis).
  uint64_t misPartitionFailures = 0;
  uint64_t misPartitionChecks = 0;
  std::array<DiscardExample, kDiscardExamples> discardExamples{};
  size_t discardExampleCount = 0;

  void noteDiscard(const DiscardExample& e) {
    if (discardExampleCount < kDiscardExamples) discardExamples[discardExampleCount++] = e;
  }

  // Every discarded contribution: per technique for the bidirectional tracer, whole samples for
  // the path tracer.
  DiscardCounts discardedCounts() const {
    DiscardCounts d = discardedSamples;
    for (const TechniqueCounters& t : techniques) d += t.discarded;
    return d;
  }
  uint64_t discarded() const { return discardedCounts().total(); }
  uint64_t totalRays() const { return rays + shadowRays; }
  // Time of the walks and of every technique's connections, while timing was on.
  uint64_t timedNanoseconds() const {
    uint64_t ns = cameraWalk.nanoseconds + lightWalk.nanoseconds + mergePass.nanoseconds + mergeSearch.nanoseconds;
    for (const TechniqueCounters& t : techniques) ns += t.nanoseconds;
    return ns;
  }
  TechniqueCounters& technique(Technique x) { return techniques[techniqueSlot(x)]; }
  const TechniqueCounters& technique(Technique x) const { return techniques[techniqueSlot(x)]; }
  TechniqueCounters& technique(int s, int t) { return technique(Technique{s, t}); }
  const TechniqueCounters& technique(int s, int t) const { return technique(Technique{s, t}); }

  Counters& operator+=(const Counters& o) {
    cameraSamples += o.cameraSamples;
    rays += o.rays;
    shadowRays += o.shadowRays;
    discardedSamples += o.discardedSamples;
    for (size_t i = 0; i < techniques.size(); ++i) techniques[i] += o.techniques[i];
    cameraWalk += o.cameraWalk;
    lightWalk += o.lightWalk;
    mergePass += o.mergePass;
    mergeSearch += o.mergeSearch;
    timedSamples += o.timedSamples;
    misPartitionFailures += o.misPartitionFailures;
    misPartitionChecks += o.misPartitionChecks;
    for (size_t i = 0; i < o.discardExampleCount; ++i) noteDiscard(o.discardExamples[i]);
    return *this;
  }
};

// Files a contribution that isValidContribution refused under its reason.
inline void countDiscarded(const Spectrum& L, DiscardCounts& d) {
  if (glm::any(glm::isnan(L))) ++d.nan;
  else if (glm::any(glm::isinf(L))) ++d.inf;
  else ++d.negative;
}
inline void countDiscarded(const Spectrum& L, Counters& c) { countDiscarded(L, c.discardedSamples); }

}  // namespace pathlab
