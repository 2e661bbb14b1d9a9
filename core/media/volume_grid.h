// A heterogeneous medium's density in world space, and the two estimators of the null-scattering
// path integral that run on it (Miller, Georgiev and Jarosz 2019; issue 35):
//   - delta tracking (Woodcock et al. 1965) samples the free-flight distance against a majorant
//     sigma_bar >= sigma_t(x): tentative collisions at rate sigma_bar, each real with probability
//     sigma_t(x) / sigma_bar and null otherwise;
//   - ratio tracking (Novak, Selle and Jarosz 2014) estimates the transmittance of a segment as the
//     product of sigma_n(x_i) / sigma_bar over tentative collisions x_i sampled at rate sigma_bar.
// Both are unbiased for any majorant; a tighter one costs fewer collisions (the majorant grid).
//
// Colour: the extinction is density(x) times a per-channel sigma_t, so the majorant is scalar (the
// largest channel) and the choices use channel averages, with per-channel weights (spectral
// tracking, Kutz et al. 2017, with P_real = avg sigma_t / sigma_bar and P_null = avg sigma_n /
// sigma_bar): a real collision weighs sigma_s(x) / avg sigma_t(x), a null one sigma_n / avg
// sigma_n. In a grey medium both weights are the albedo and one, delta tracking's classic form.
//
// MIS: pathlab's bidirectional densities leave the media's distance probabilities out, for every
// technique alike (core/bpt/subpath.cpp), so null vertices need no place in them: the weights stay
// a partition of unity, and tracking's estimates enter only the throughput. The path tracer's
// equiangular technique, whose weights do use the distance density, declines heterogeneous media.
#pragma once

#include "core/media/density_grid.h"
#include "core/media/medium.h"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>

#include <cmath>
#include <memory>

namespace pathlab {

struct VolumeGrid {
  DensityGrid density;         // densityScale already applied
  MajorantGrid majorant;       // of density
  Mat4 worldToIndex{1.f};      // (node x grid transform)^-1

  VolumeGrid() = default;
  VolumeGrid(DensityGrid d, const Mat4& indexToWorld)
      : density(std::move(d)), majorant(density), worldToIndex(glm::inverse(indexToWorld)) {}

  Vec3 toIndex(const Vec3& p) const { return Vec3(worldToIndex * Vec4(p, 1.f)); }
  Vec3 toIndexDirection(const Vec3& d) const { return Mat3(worldToIndex) * d; }
  float densityAt(const Vec3& world) const { return density.lookup(toIndex(world)); }
};

// A tentative collision's bound: a walk that meets more than this many in one segment (an absurd
// majorant against a tiny step) stops there, absorbed: a finite walk rather than a hang.
inline constexpr int kMaxTentativeCollisions = 1 << 20;

namespace detail {
inline float average(const Spectrum& s) { return (s.r + s.g + s.b) / 3.f; }
}  // namespace detail

// The tentative collisions of o + t d (world, d unit) over [0, tMax): exponential steps at the
// rate sigma_bar = the majorant cell's density x the largest channel of `sigmaT` (per unit
// density), cell by cell (memoryless: a step past a cell's end restarts at the next cell).
// collide(t, density at t, sigma_bar) returns false to stop. Returns false when stopped by
// collide or by kMaxTentativeCollisions (`exhausted` then true).
template <class Rng, class Collide>
bool trackCollisions(const VolumeGrid& grid, const Spectrum& sigmaT, const Vec3& o, const Vec3& d, float tMax, Rng& rng,
                     bool& exhausted, Collide&& collide) {
  const float sigmaMax = maxComponent(sigmaT);
  const Vec3 oi = grid.toIndex(o), di = grid.toIndexDirection(d);
  int collisions = 0;
  bool finished = true;
  exhausted = false;
  grid.majorant.traverse(oi, di, 0.f, tMax, [&](float t0, float t1, float majorantDensity) {
    const float sigmaBar = majorantDensity * sigmaMax;
    if (!(sigmaBar > 0.f)) return true;
    for (float t = t0;;) {
      t -= std::log1p(-rng.next1D()) / sigmaBar;
      if (!(t < t1)) return true;
      if (++collisions > kMaxTentativeCollisions) exhausted = true;
      if (exhausted || !collide(t, grid.density.lookup(oi + t * di), sigmaBar)) return finished = false;
    }
  });
  return finished;
}

// Delta tracking in the medium whose extinction and scattering at density 1 are perUnit's. The
// DistanceSample's weight is the throughput factor (sampleDistance's contract): the product of
// the collisions' weights above; a walk that exhausts its collisions ends absorbed (black).
template <class Rng>
DistanceSample deltaTrack(const HomogeneousMedium& perUnit, const VolumeGrid& grid, const Vec3& o, const Vec3& d,
                          float tMax, Rng& rng) {
  DistanceSample out;
  bool exhausted = false;
  trackCollisions(grid, perUnit.sigmaT, o, d, tMax, rng, exhausted, [&](float t, float rho, float sigmaBar) {
    const Spectrum sigmaT = rho * perUnit.sigmaT;
    const float real = detail::average(sigmaT);
    if (rng.next1D() * sigmaBar < real) {
      out.scattered = true;
      out.t = t;
      out.weight *= rho * perUnit.sigmaS / real;
      return false;
    }
    const Spectrum sigmaN = glm::max(Spectrum(sigmaBar) - sigmaT, Spectrum(0.f));
    const float null = detail::average(sigmaN);
    if (null > 0.f) out.weight *= sigmaN / null;
    return true;
  });
  if (exhausted) {
    out.scattered = true;
    out.weight = Spectrum(0.f);
  }
  return out;
}

// Ratio tracking's estimate of the transmittance along o + t d over [0, tMax) (t may be infinite:
// the field is zero outside the grid). Once every channel's estimate is below 0.1, each further
// collision continues with probability 1/2 and doubles the estimate (Russian roulette, unbiased),
// so thick media cost a bounded number of collisions.
template <class Rng>
Spectrum ratioTrack(const HomogeneousMedium& perUnit, const VolumeGrid& grid, const Vec3& o, const Vec3& d, float tMax,
                    Rng& rng) {
  Spectrum T(1.f);
  bool exhausted = false;
  trackCollisions(grid, perUnit.sigmaT, o, d, tMax, rng, exhausted, [&](float, float rho, float sigmaBar) {
    T *= glm::max(Spectrum(1.f) - (rho / sigmaBar) * perUnit.sigmaT, Spectrum(0.f));
    if (maxComponent(T) < 0.1f) {
      if (rng.next1D() < 0.5f) {
        T = Spectrum(0.f);
        return false;
      }
      T *= 2.f;
    }
    return true;
  });
  return exhausted ? Spectrum(0.f) : T;
}

}  // namespace pathlab
