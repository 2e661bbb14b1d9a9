// Path tracing with next-event estimation and MIS; path length counted in edges.
#include "core/pt/path_tracer.h"

#include "core/sampling/mis.h"
#include "core/sampling/russian_roulette.h"

namespace pathlab {

PathTracer::PathTracer(const Scene& scene, const PathTracerOptions& options)
    : scene_(scene), maxLength_(options.maxLength), russianRoulette_(options.russianRoulette) {}

// One light sample for the vertex `hit`: the (s = 1) connection of the path tracer. Weighted
// against BSDF sampling of the same path with the power heuristic.
Spectrum PathTracer::sampleDirect(const SurfaceHit& hit, const Bsdf& bsdf, const Vec3& wo,
                                  Pcg32& rng, Counters& counters) const {
  const LightSet& lights = scene_.lights();
  float lightPmf = 0.f, uLight = rng.next1D();
  const Vec2 uPos = rng.next2D();
  const int li = lights.sample(uLight, &lightPmf);
  if (li < 0 || lightPmf <= 0.f) return Spectrum(0.f);
  const Light& light = lights[static_cast<size_t>(li)];
  const LightLiSample ls = light.sampleLi(hit.p, uPos);
  if (ls.pdfW <= 0.f || isBlack(ls.Li)) return Spectrum(0.f);
  const BsdfEval ev = bsdf.eval(wo, ls.wi, TransportMode::Radiance);
  if (isBlack(ev.f)) return Spectrum(0.f);
  ++counters.shadowRays;
  const bool unblocked = light.isInfinite() ? scene_.visibleToInfinity(hit.p, hit.ng, hit.pError, ls.wi)
                                            : scene_.visible(hit.p, hit.ng, hit.pError, ls.pLight, ls.nLight, ls.pError);
  if (!unblocked) return Spectrum(0.f);
  const float pdfLight = lightPmf * ls.pdfW;
  const float weight = ls.isDelta ? 1.f : powerHeuristic(pdfLight, ev.pdfFwdW);
  return ev.f * ls.Li * (absDot(ls.wi, hit.ns) * weight / pdfLight);
}

// The environment seen by a ray that left the scene in direction w, weighted against next-event
// estimation's sampling of the same direction (power heuristic, as for area lights).
Spectrum PathTracer::environmentSeen(const Vec3& w, bool prevDelta, float prevPdfW) const {
  const LightSet& lights = scene_.lights();
  const Light& light = lights[static_cast<size_t>(lights.environment())];
  const Spectrum Le = light.environmentLight()->Le(w);
  if (prevDelta || isBlack(Le)) return Le;
  const float pdfLight = lights.pmf(lights.environment()) * light.environmentLight()->pdfDirection(w);
  return Le * powerHeuristic(prevPdfW, pdfLight);
}

Spectrum PathTracer::Li(const Ray& cameraRay, Pcg32& rng, Counters& counters) const {
  Spectrum L(0.f), beta(1.f);
  Ray ray = cameraRay;
  bool prevDelta = true;  // the camera vertex: emitters seen directly get weight one
  float prevPdfW = 0.f;
  Vec3 prevP = ray.o;
  for (int edges = 1;; ++edges) {
    ++counters.rays;
    const std::optional<SurfaceHit> hit = scene_.intersect(ray);
    if (!hit) {
      if (scene_.lights().environment() >= 0) L += beta * environmentSeen(ray.d, prevDelta, prevPdfW);
      break;
    }
    const Vec3 wo = -ray.d;

    if (hit->light >= 0) {
      const Light& light = scene_.lights()[static_cast<size_t>(hit->light)];
      const Spectrum Le = light.radiance(hit->ng, scene_.emissionUv(hit->material, hit->uv, hit->uv1), wo);
      if (!isBlack(Le)) {
        float weight = 1.f;
        if (!prevDelta) {
          const float pdfLight = scene_.lights().pmf(hit->light) * light.pdfLi(prevP, hit->p, hit->ng);
          weight = powerHeuristic(prevPdfW, pdfLight);
        }
        L += beta * Le * weight;
      }
    }
    if (edges >= maxLength_) break;

    const Bsdf bsdf = scene_.bsdf(hit->material, ShadingInputs{hit->uv, hit->uv1, hit->color}, hit->ns, hit->ng);
    if (bsdf.hasNonDelta()) L += beta * sampleDirect(*hit, bsdf, wo, rng, counters);

    const float uLobe = rng.next1D();
    const Vec2 uDir = rng.next2D();
    const std::optional<BsdfSample> bs = bsdf.sample(wo, uDir, uLobe, TransportMode::Radiance);
    if (!bs || bs->pdfFwdW <= 0.f || isBlack(bs->f)) break;
    beta *= bs->f * (absDot(bs->wi, hit->ns) / bs->pdfFwdW);
    prevDelta = bs->isDelta;
    prevPdfW = bs->pdfFwdW;
    prevP = hit->p;
    ray = Ray{offsetRayOrigin(hit->p, hit->pError, hit->ng, bs->wi), bs->wi};

    // Russian roulette on the throughput (unbiased: survivors are reweighted by 1/q). The survival
    // probability is not capped below one: with a cap of 0.95, paths of the mean length
    // 1 / (1 - albedo) = 1000 of an albedo-0.999 furnace survive with probability 0.95^1000, and
    // the estimate, unbiased in theory, is wrong for any practical sample count.
    if (russianRoulette_ && edges >= kRussianRouletteStart) {
      const float q = glm::min(maxComponent(beta), 1.f);
      if (!(q > 0.f) || rng.next1D() >= q) break;
      beta /= q;
    }
  }
  return L;
}

}  // namespace pathlab
