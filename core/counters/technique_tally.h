// The counting and timing sink of the bidirectional kernel: what one technique's try came to (zero,
// blocked, contributed, discarded), its shadow rays and, on a timed sample, its time. The kernel
// reports each outcome here once; the counters' meaning lives in this file, not in the kernel.
#pragma once

#include "core/counters/counters.h"
#include "core/counters/technique_timer.h"

#include <type_traits>

namespace pathlab {

// One technique's try. kTimed: a timed sample's (BidirTracer::setTiming, one in kTimedSampleStride),
// which adds the try's time, up to its outcome, to the technique's nanoseconds. A template on it,
// so that untimed tries carry no timer at all (even an idle ScopedTimer cost 0.4 % of a sample's
// instructions; docs/benchmarks.md, session 13).
template <bool kTimed>
class TechniqueTally {
 public:
  TechniqueTally(Counters& counters, Technique x)
      : counters_(counters), technique_(counters.technique(x)), x_(x), timer_(technique_.nanoseconds) {
    ++technique_.tried;
  }

  void shadowRay() {
    ++counters_.shadowRays;
    ++technique_.shadowRays;
  }
  // The try's outcome; its time ends here (what follows is the outputs' work, not the technique's).
  void zero() {
    timer_.stop();
    ++technique_.zero;
  }
  void blocked() {
    timer_.stop();
    ++technique_.blocked;
  }
  void contributed() {
    timer_.stop();
    ++technique_.contributed;
  }
  // A contribution refused at the door (NaN, Inf or negative, or a splat off the film), filed under
  // its reason with the sample that made it, for `pathlab render --replay`.
  void discard(const Spectrum& value, const SampleId& id) {
    countDiscarded(value, technique_.discarded);
    counters_.noteDiscard(DiscardExample{id.x, id.y, id.sample, x_.s, x_.t, value});
  }

 private:
  struct NoTimer {
    explicit NoTimer(uint64_t&) {}
    void stop() {}
  };
  struct OnTimer : ScopedTimer {
    explicit OnTimer(uint64_t& total) : ScopedTimer(true, total) {}
  };

  Counters& counters_;
  TechniqueCounters& technique_;
  Technique x_;
  std::conditional_t<kTimed, OnTimer, NoTimer> timer_;
};

}  // namespace pathlab
