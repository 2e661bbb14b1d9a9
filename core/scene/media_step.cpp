// The walk's step through media and index-matched boundaries.
#include "core/scene/media_step.h"

#include "core/media/volume_grid.h"

namespace pathlab {

namespace {
// A ray crossing more boundaries than this without meeting anything (a numerical loop along
// coplanar boundary triangles) is dropped: a finite walk, at the cost of one path.
constexpr int kMaxStepCrossings = 64;
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
        step.weight *= ratioTrack(m, *grid, ray.o, ray.d, tMax, rng);  // absorbs only
      } else if (m.scatters()) {
        // A heterogeneous medium: delta tracking against its majorant grid (volume_grid.h);
        // a homogeneous one: the closed-form distance sampling.
        DistanceSample ds;
        if (grid) {
          ds = deltaTrack(m, *grid, ray.o, ray.d, tMax, rng);
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
