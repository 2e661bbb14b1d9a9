// Work and health counters of a render: rays traced and samples the film refused.
#pragma once

#include "core/math/types.h"

#include <cstdint>

namespace pathlab {

struct Counters {
  uint64_t cameraSamples = 0;
  uint64_t rays = 0;          // closest-hit queries
  uint64_t shadowRays = 0;    // visibility queries
  uint64_t discardedNaN = 0;  // contributions with a NaN channel
  uint64_t discardedInf = 0;  // ... with an infinite channel
  uint64_t discardedNegative = 0;

  uint64_t discarded() const { return discardedNaN + discardedInf + discardedNegative; }
  uint64_t totalRays() const { return rays + shadowRays; }
  Counters& operator+=(const Counters& o) {
    cameraSamples += o.cameraSamples;
    rays += o.rays;
    shadowRays += o.shadowRays;
    discardedNaN += o.discardedNaN;
    discardedInf += o.discardedInf;
    discardedNegative += o.discardedNegative;
    return *this;
  }
};

// Files a contribution the film refused (isValidContribution false) under its reason.
inline void countDiscarded(const Spectrum& L, Counters& c) {
  if (glm::any(glm::isnan(L))) ++c.discardedNaN;
  else if (glm::any(glm::isinf(L))) ++c.discardedInf;
  else ++c.discardedNegative;
}

}  // namespace pathlab
