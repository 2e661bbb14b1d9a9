// Cheap timing of the bidirectional tracer's walks and techniques: the time-stamp counter read
// around a piece of work, converted to nanoseconds, on a sampled fraction of camera samples.
#pragma once

#include <cstdint>

namespace pathlab {

// One camera sample in this many is timed, picked by the sample's own random key: the shares of
// the walks and the techniques are estimated without bias from an eighth of the samples (tens of
// thousands a pass at viewer resolutions), and timing costs an eighth of what timing every sample
// would (about 11% of a bidirectional pass, measured; see docs/benchmarks.md).
inline constexpr uint64_t kTimedSampleStride = 8;

// The time-stamp counter where there is one (15 ns a read on the reference VM against 35 ns for
// steady_clock; constant_tsc: it ticks at one rate on every core), else steady_clock in ns.
uint64_t ticks();
// Nanoseconds between two tick readings; 0 if the thread moved to a core whose counter lags.
uint64_t elapsedNanoseconds(uint64_t start, uint64_t end);

// Adds the time from construction to stop() (or to the end of the scope, for early exits) to
// `total`, only when `on`.
class ScopedTimer {
 public:
  ScopedTimer(bool on, uint64_t& total) : total_(on ? &total : nullptr), start_(on ? ticks() : 0) {}
  ~ScopedTimer() { stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;
  void stop() {
    if (total_) *total_ += elapsedNanoseconds(start_, ticks());
    total_ = nullptr;
  }

 private:
  uint64_t* total_;
  uint64_t start_;
};

}  // namespace pathlab
