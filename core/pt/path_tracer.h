// The unidirectional path tracer: next-event estimation and BSDF sampling combined with the power
// heuristic (Veach 1997, sec. 9.2.4). Independent of the bidirectional core by design: it is the
// reference the BPT is tested against and the baseline users compare with.
#pragma once

#include "core/bsdf/bsdf.h"
#include "core/math/rng.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"

namespace pathlab {

struct PathTracerOptions {
  int maxLength = 10;           // edges
  bool russianRoulette = true;  // sampling/russian_roulette.h
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
  // The same at a scattering point p in medium `medium` (phase function, no cosine).
  Spectrum sampleDirectInMedium(const Vec3& p, int medium, const Vec3& wo, Pcg32& rng, Counters& counters) const;
  Spectrum environmentSeen(const Vec3& w, bool prevDelta, float prevPdfW, const LightSampleContext& prev) const;
  const Scene& scene_;
  int maxLength_;
  bool russianRoulette_;
};

}  // namespace pathlab
