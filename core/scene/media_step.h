// One step of a random walk (the bidirectional walks and the path tracer share it): from a ray in
// a known medium to what it meets next, a surface, a scattering event in a medium, or nothing. In a
// scene with media (issue 16) it samples the distance in every medium it crosses (pbrt-v3
// HomogeneousMedium::Sample, spectral MIS over the channels; delta tracking in a density grid) and passes straight through
// index-matched boundaries, which change only the medium; in a scene without, it is one ray cast.
#pragma once

#include "core/math/rng.h"
#include "core/sampling/primary_samples.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"

#include <optional>

namespace pathlab {

enum class MediaStepKind : uint8_t { Surface, Medium, Escaped, Absorbed };

struct MediaStep {
  MediaStepKind kind = MediaStepKind::Absorbed;
  std::optional<SurfaceHit> hit;  // Surface
  Vec3 p{0.f};                    // Medium: the scattering point
  int medium = -1;                // Medium: the medium it lies in (after any boundary the step crossed)
  // The segments' transmittance (and sigma_s at a scattering point) over the probability with
  // which the distance sampling produced this outcome; one in vacuum.
  Spectrum weight{1.f};
  // The ray's first segment, up to the first surface it meets (index-matched or not; infinite
  // when none), and where along it the step scattered (-1: not within it). Equiangular sampling
  // places vertices in that segment only (core/pt/path_tracer.cpp).
  float firstSegment = 0.f;
  float firstSegmentT = -1.f;
};

// Traces `ray` starting in `medium` (-1: none) in a scene with media, counting each ray it casts in
// counters.rays. Consumes two random numbers per homogeneous medium segment it samples a distance
// in (none in vacuum, and none in a purely absorbing homogeneous medium, whose transmittance is
// applied as a weight); in a heterogeneous medium (a density grid) delta tracking, or ratio
// tracking when it only absorbs, draws as many as its tentative collisions need.
// Rng: Pcg32, or a primary-sample stream (core/sampling/primary_samples.h) for Metropolis.
template <class Rng>
MediaStep traceThroughMedia(const Scene& scene, Ray ray, int medium, Rng& rng, Counters& counters);
extern template MediaStep traceThroughMedia(const Scene&, Ray, int, Pcg32&, Counters&);
extern template MediaStep traceThroughMedia(const Scene&, Ray, int, PrimarySampleStream&, Counters&);

// Without media: one ray cast, every hit a Surface (index-matched or not), the weight exactly one.
inline MediaStep traceInVacuum(const Scene& scene, const Ray& ray, Counters& counters) {
  ++counters.rays;
  MediaStep step{MediaStepKind::Surface, scene.intersect(ray)};
  if (!step.hit) step.kind = MediaStepKind::Escaped;
  return step;
}

// The walks' step (randomWalk, PathTracer::Li). Inline, each branch returning its step in place: a
// call and a copy of the step per vertex cost a bidirectional sample 1 % of its instructions.
template <class Rng>
inline MediaStep traceStep(const Scene& scene, const Ray& ray, int medium, Rng& rng, Counters& counters) {
  return scene.hasMedia() ? traceThroughMedia(scene, ray, medium, rng, counters) : traceInVacuum(scene, ray, counters);
}

}  // namespace pathlab
