// The walk's step through media and index-matched boundaries.
#include "core/scene/media_step.h"

#include "core/media/volume_grid.h"

#include <bit>
#include <type_traits>

namespace pathlab {

namespace {
// A ray crossing more boundaries than this without meeting anything (a numerical loop along
// coplanar boundary triangles) is dropped: a finite walk, at the cost of one path.
constexpr int kMaxStepCrossings = 64;
}  // namespace

namespace {

// Tracking's random numbers. A walk's own Pcg32 serves directly; a Metropolis chain's primary
// sample stream gives two coordinates that seed a Pcg32 for the segment instead: tracking draws
// as many numbers as it meets tentative collisions, and a chain's state would otherwise grow by
// that many coordinates (and every mutation with it).
template <class Rng>
Pcg32 trackingRng(Rng& rng) {
  const uint64_t a = std::bit_cast<uint32_t>(rng.next1D()), b = std::bit_cast<uint32_t>(rng.next1D());
  return Pcg32(mixBits(a << 32 | b), mixBits(b ^ 0x9e3779b97f4a7c15ULL));
}

template <class Rng, class Track>
auto withTrackingRng(Rng& rng, Track&& track) {
  if constexpr (std::is_same_v<Rng, Pcg32>) {
    return track(rng);
  } else {
    Pcg32 local = trackingRng(rng);
    return track(local);
  }
}

}  // namespace

template <class Rng>
MediaStep traceThroughMedia(const Scene& scene, Ray ray, int medium, Rng& rng, Counters& counters) {
  MediaStep step;
  for (int crossing = 0; crossing < kMaxStepCrossings; ++crossing) {
    ++counters.rays;
    std::optional<SurfaceHit> hit = scene.intersect(ray);
    const float tMax = hit ? hit->t : std::numeric_limits<float>::infinity();
    if (crossing == 0) step.firstSegment = tMax;
    if (medium >= 0) {
      const HomogeneousMedium& m = scene.medium(medium);
      const VolumeGrid* grid = scene.mediumGrid(medium);
      if (grid && !m.scatters()) {
        // Absorbs only.
        step.weight *= withTrackingRng(rng, [&](auto& r) { return ratioTrack(m, *grid, ray.o, ray.d, tMax, r); });
      } else if (m.scatters()) {
        // A heterogeneous medium: delta tracking against its majorant grid (volume_grid.h);
        // a homogeneous one: the closed-form distance sampling.
        DistanceSample ds;
        if (grid) {
          ds = withTrackingRng(rng, [&](auto& r) { return deltaTrack(m, *grid, ray.o, ray.d, tMax, r); });
        } else {
          const float uChannel = rng.next1D(), u = rng.next1D();
          ds = sampleDistance(m, tMax, uChannel, u);
        }
        step.weight *= ds.weight;
        if (ds.scattered) {
          step.kind = isBlack(step.weight) ? MediaStepKind::Absorbed : MediaStepKind::Medium;
          step.p = ray.o + ds.t * ray.d;
          step.medium = medium;
          if (crossing == 0) step.firstSegmentT = ds.t;
          return step;
        }
      } else {
        step.weight *= m.transmittance(tMax);
      }
      if (isBlack(step.weight)) return step;  // Absorbed
    }
    if (!hit) {
      step.kind = MediaStepKind::Escaped;
      return step;
    }
    if (!hit->indexMatched) {
      step.kind = MediaStepKind::Surface;
      step.hit = std::move(hit);
      return step;
    }
    medium = hit->media.toward(hit->ng, ray.d);
    ray = Ray{offsetRayOrigin(hit->p, hit->pError, hit->ng, ray.d), ray.d};
  }
  return step;  // Absorbed
}

template MediaStep traceThroughMedia(const Scene&, Ray, int, Pcg32&, Counters&);
template MediaStep traceThroughMedia(const Scene&, Ray, int, PrimarySampleStream&, Counters&);

}  // namespace pathlab
