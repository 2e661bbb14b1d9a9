// The time-stamp counter and its conversion to nanoseconds, measured once against steady_clock.
#include "core/counters/technique_timer.h"

#include <algorithm>
#include <chrono>
#include <thread>
#if defined(__x86_64__)
#include <x86intrin.h>
#endif

namespace pathlab {

namespace {

#if defined(__x86_64__)
double nanosecondsPerTick() {
  static const double factor = [] {
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t c0 = __rdtsc();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const auto t1 = std::chrono::steady_clock::now();
    const uint64_t c1 = __rdtsc();
    return std::chrono::duration<double, std::nano>(t1 - t0).count() / static_cast<double>(std::max<uint64_t>(c1 - c0, 1));
  }();
  return factor;
}
#else
double nanosecondsPerTick() { return 1.0; }
#endif

}  // namespace

uint64_t ticks() {
#if defined(__x86_64__)
  return __rdtsc();
#else
  return static_cast<uint64_t>(
      std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch()).count());
#endif
}

uint64_t elapsedNanoseconds(uint64_t start, uint64_t end) {
  return end > start ? static_cast<uint64_t>(static_cast<double>(end - start) * nanosecondsPerTick()) : 0;
}

}  // namespace pathlab
