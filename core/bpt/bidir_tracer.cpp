// BidirTracer: generate, connect, weigh, accumulate.
#include "core/bpt/bidir_tracer.h"

#include "core/bpt/connect.h"

namespace pathlab {

TechniqueSet techniquesOf(const RenderSettings& settings) {
  TechniqueSet set = TechniqueSet::parse(settings.techniques, settings.maxLength);
  if (settings.integrator == IntegratorKind::Lt)
    for (int k = 1; k <= settings.maxLength; ++k)
      for (int s = 0; s <= k; ++s)
        if (k + 1 - s != 1) set.disable(s, k + 1 - s);
  return set;
}

BidirTracer::BidirTracer(const Scene& scene, const Camera& camera, const RenderSettings& settings)
    : scene_(scene),
      camera_(camera),
      maxLength_(settings.maxLength),
      russianRoulette_(settings.russianRoulette),
      techniques_(techniquesOf(settings)),
      mis_(settings.mis) {}

Spectrum BidirTracer::sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, Film* film,
                             Counters& counters) const {
  // Per-thread buffers sized once: no allocation per sample.
  thread_local CameraSubpath cameraPath;
  thread_local LightSubpath lightPath;
  const int nt = generateCameraSubpath(scene_, camera_, pRaster, uLens, cameraRng,
                                       WalkOptions{maxLength_ + 1, russianRoulette_}, cameraPath, counters);
  const int ns = generateLightSubpath(scene_, lightRng, WalkOptions{maxLength_, russianRoulette_}, lightPath, counters);

  Spectrum L(0.f);
  const float ratio = lightTracingRatio();
  for (int t = 1; t <= nt; ++t)
    for (int s = 0; s <= ns; ++s) {
      const int k = s + t - 1;
      if (k < 1 || k > maxLength_ || !techniques_.contains(s, t)) continue;
      const Connection c = connect(scene_, camera_, lightPath.data(), s, cameraPath.data(), t, cameraRng, counters);
      if (isBlack(c.L)) continue;
      const MisPath path{lightPath.data(), s, cameraPath.data(), t, c.hasSampled ? &c.sampled : nullptr};
      const float w = misWeight(scene_, camera_, path, techniques_, mis_, ratio);
      if (w == 0.f) continue;
      const Spectrum contribution = c.L * w;
      if (t == 1) {
        if (film && !film->splat(c.pRaster, contribution)) countDiscarded(contribution, counters);
      } else {
        L += contribution;
      }
    }
  return L;
}

}  // namespace pathlab
