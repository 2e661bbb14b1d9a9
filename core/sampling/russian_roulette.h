// Russian roulette, one policy for the path tracer and both bidirectional walks (path_tracer.cpp,
// subpath.cpp); the path tracer and the camera walk also start it alike, so that their paths of a
// given length are ended by the same rule.
#pragma once

#include "core/math/rng.h"
#include "core/math/types.h"

namespace pathlab {

// Scatterings a walk makes before roulette may end it: the first is always continued.
inline constexpr int kRussianRouletteStart = 2;

// Which scatterings count toward kRussianRouletteStart. A camera walk (and the path tracer) does
// not count its delta bounces: the first surface it sees by diffuse or glossy scattering, directly
// or in a mirror or through glass, always gets its next bounce, as a surface seen directly does.
// Counting every scattering there ended the reflections in the mirror sphere of
// cornell-spheres.gltf one bounce earlier than the room seen directly (the mirror was the first
// scattering, the wall it shows the second): error per sample 1.3x that of counting non-delta
// ones, at the same cost. A light walk counts every scattering: its caustic vertex (light -> glass
// -> glass -> floor) is already stored where roulette is decided, and continuing past it, on the
// fog scene's dark floor, cost its BPT 25 % more time for 8 % less error (docs/benchmarks.md,
// "Session 20: the roulette's start").
enum class RouletteCount : uint8_t { NonDeltaScatterings, Scatterings };

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
  RussianRoulette(const Spectrum& beta, RouletteCount count) : last_(beta), count_(count) {}

  // The survival probability after a scattering that took the throughput from `last` to `beta`.
  static float continuation(const Spectrum& last, const Spectrum& beta, bool delta) {
    if (delta) return 1.f;
    return glm::min(maxComponent(beta / glm::max(last, Spectrum(1e-30f))), 1.f);
  }

  // Called after every scattering with the walk's throughput `beta`: false ends the walk; a
  // survivor's beta is divided by q. Draws a number only when q < 1.
  template <class Rng>
  bool survives(Spectrum& beta, bool delta, Rng& rng) {
    if (!delta || count_ == RouletteCount::Scatterings) ++scatterings_;
    const float q = scatterings_ < kRussianRouletteStart ? 1.f : continuation(last_, beta, delta);
    if (q < 1.f) {
      if (!(q > 0.f) || rng.next1D() >= q) return false;
      beta /= q;
      weight_ /= q;
    }
    last_ = beta;
    return true;
  }
  // The product of 1 / q over the walk's decisions so far: the factor its throughput carries beyond
  // the path's contribution over its density (which leaves roulette out).
  float weight() const { return weight_; }

 private:
  Spectrum last_;  // the throughput at the last decision
  RouletteCount count_;
  int scatterings_ = 0;  // those counted so far
  float weight_ = 1.f;
};

}  // namespace pathlab
