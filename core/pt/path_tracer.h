// The unidirectional path tracer: next-event estimation and BSDF sampling combined with the power
// heuristic (Veach 1997, sec. 9.2.4). Independent of the bidirectional core by design: it is the
// reference the BPT is tested against and the baseline users compare with.
#pragma once

#include "core/bsdf/bsdf.h"
#include "core/math/rng.h"
#include "core/counters/counters.h"
#include "core/media/medium_sampling.h"
#include "core/scene/scene.h"

namespace pathlab {

struct PathTracerOptions {
  int maxLength = 10;           // edges
  bool russianRoulette = true;  // sampling/russian_roulette.h
  MediumSampling mediumSampling = MediumSampling::Mis;  // media only (core/media/medium_sampling.h)
};

// Where a scattering vertex lies on the ray that reached it, for the equiangular technique's
// density there: the ray, its first segment's length and the vertex's distance along it, and
// distance sampling's density of that distance. Invalid when the vertex lies past the first
// segment (equiangular sampling cannot place it there).
struct MediumVertexSegment {
  Ray ray;
  float tMax = 0.f;
  float t = -1.f;
  float pdfDistance = 0.f;
  bool valid() const { return t >= 0.f && pdfDistance > 0.f; }
};

class PathTracer {
 public:
  PathTracer(const Scene& scene, const PathTracerOptions& options);
  // Radiance arriving along a camera ray (the estimate of one camera sample, unfiltered) whose
  // origin lies in `medium` (Scene::mediumAt of the camera; -1: none).
  Spectrum Li(const Ray& cameraRay, Pcg32& rng, Counters& counters, int medium = -1) const;

 private:
  Spectrum sampleDirect(const SurfaceHit& hit, const Bsdf& bsdf, const Vec3& wo, Pcg32& rng,
                        Counters& counters) const;
  // The same at a scattering point p in medium `medium` (phase function, no cosine), placed by
  // distance sampling on `segment`.
  Spectrum sampleDirectInMedium(const Vec3& p, int medium, const Vec3& wo, const MediumVertexSegment& segment,
                                Pcg32& rng, Counters& counters) const;
  // The equiangular technique on the first segment (length tMax) of `ray`, which starts in the
  // scattering medium `medium`: a light and a point y on it, a vertex on the segment by
  // equiangular sampling toward y, and the connection to y.
  Spectrum sampleEquiangularDirect(const Ray& ray, int medium, float tMax, Pcg32& rng, Counters& counters) const;
  // The equiangular technique's density of a vertex on `segment` that connects to the point y of
  // light `light`, over distance sampling's density of it, times the light's choice from the
  // segment's origin: the factor that turns next-event estimation's density (pmf x pdfW) into the
  // equiangular one. Zero where equiangular sampling is off or cannot place the vertex.
  float equiangularRatio(const MediumVertexSegment& segment, int light, const Vec3& y) const;
  // The density with which distance sampling and next-event estimation (A) take part in the
  // weights, given the equiangular one: none under `equiangular` where equiangular sampling can
  // sample the path (that mode leaves it every path it can sample), pdfLight otherwise.
  float nextEventDensity(float pdfLight, float pdfEquiangular) const {
    return mediumSampling_ == MediumSampling::Equiangular && pdfEquiangular > 0.f ? 0.f : pdfLight;
  }
  Spectrum environmentSeen(const Vec3& w, bool prevDelta, float prevPdfW, const LightSampleContext& prev) const;
  const Scene& scene_;
  int maxLength_;
  bool russianRoulette_;
  MediumSampling mediumSampling_;
};

}  // namespace pathlab
