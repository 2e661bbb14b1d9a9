// The primary sample vector's lazy mutations (Kelemen et al. 2002, sec. 3; pbrt-v4 MLTSampler).
#include "core/sampling/primary_samples.h"

#include <cmath>

namespace pathlab {

namespace {
// A standard normal from two uniforms (Box and Muller 1958); u1 in [0, 1) is mapped into (0, 1].
float standardNormal(Pcg32& rng) {
  const float u1 = 1.f - rng.next1D(), u2 = rng.next1D();
  return std::sqrt(-2.f * std::log(u1)) * std::cos(2.f * kPi * u2);
}
}  // namespace

float PrimarySamples::get(size_t index) {
  if (index >= x_.size()) x_.resize(index + 1);
  Coordinate& x = x_[index];
  if (x.modified < iteration_) mutate(x);
  if (readLog_) [[unlikely]]
    readLog_->emplace_back(index, x.value);
  return x.value;
}

void PrimarySamples::mutate(Coordinate& x) {
  // A coordinate last set before the last accepted large step takes that step's fresh value first
  // (a new one too, never set): the large step replaced it even though no path read it then.
  if (x.modified < lastLargeStep_) {
    x.value = rng_.next1D();
    x.modified = lastLargeStep_;
  }
  x.backup = x.value;
  x.backupModified = x.modified;
  if (largeStep_) {
    x.value = rng_.next1D();
  } else {
    // The small steps it missed since it was last set, and this one: their sum is one normal of
    // variance sigma^2 times their count. Wrapped into [0, 1) (the primary space is a torus, so
    // the step stays symmetric).
    const auto steps = static_cast<float>(iteration_ - x.modified);
    x.value += standardNormal(rng_) * sigma_ * std::sqrt(steps);
    x.value -= std::floor(x.value);
    if (!(x.value < 1.f)) x.value = 0.f;  // -tiny - floor(-tiny) rounds to 1
  }
  x.modified = iteration_;
}

void PrimarySamples::reject() {
  for (Coordinate& x : x_)
    if (x.modified == iteration_) {
      x.value = x.backup;
      x.modified = x.backupModified;
    }
  --iteration_;
}

}  // namespace pathlab
