// Russian roulette, one policy for the path tracer and both bidirectional walks, so that their
// paths of a given length are ended by the same rule (path_tracer.cpp, subpath.cpp).
#pragma once

#include "core/math/rng.h"
#include "core/math/types.h"

namespace pathlab {

// Edges a path has before roulette may end it: the first scattering is always continued.
inline constexpr int kRussianRouletteStart = 2;

// The survival decisions of one walk (issue 31; the alternatives measured on every bundled scene
// are in docs/benchmarks.md, "Session 15: Russian roulette"). After each scattering the walk
// continues with probability q = min(1, max component of what that scattering kept of the
// throughput, f |cos| / pdf times the medium step's weight): its albedo as sampled, not the
// throughput since the walk began, which made a path that had passed a few diffuse bounces, or
// entered glass (a factor 1 / eta^2 in radiance), a candidate for ending at every later bounce.
// A delta bounce (mirror, smooth glass) always continues: it neither loses energy nor offers a
// choice of direction, and the chains through it carry the caustics and reflections. Survivors
// are divided by q (unbiased); the MIS densities leave roulette out (it is not a technique).
// Bounded: the division restores at most the largest component the throughput had before the
// scattering. Not capped below one: with a cap of 0.95, paths of the mean length
// 1 / (1 - albedo) = 1000 of an albedo-0.999 furnace survive with probability 0.95^1000, and the
// estimate, unbiased in theory, is wrong for any practical sample count.
class RussianRoulette {
 public:
  explicit RussianRoulette(const Spectrum& beta) : last_(beta) {}

  // The survival probability after a scattering that took the throughput from `last` to `beta`.
  static float continuation(const Spectrum& last, const Spectrum& beta, bool delta) {
    if (delta) return 1.f;
    return glm::min(maxComponent(beta / glm::max(last, Spectrum(1e-30f))), 1.f);
  }

  // Called after every scattering with the walk's throughput `beta` and its edge count: false
  // ends the walk; a survivor's beta is divided by q. Draws a number only when q < 1.
  bool survives(Spectrum& beta, bool delta, int edges, Pcg32& rng) {
    const float q = edges < kRussianRouletteStart ? 1.f : continuation(last_, beta, delta);
    if (q < 1.f) {
      if (!(q > 0.f) || rng.next1D() >= q) return false;
      beta /= q;
    }
    last_ = beta;
    return true;
  }

 private:
  Spectrum last_;  // the throughput at the last decision
};

}  // namespace pathlab
