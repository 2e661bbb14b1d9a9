// Path tracing with next-event estimation and MIS; path length counted in edges. In scenes with
// media, the distance to the next vertex is sampled in every medium (core/scene/media_step.h), a
// scattering point in a medium is a vertex with the phase function as its BSDF, and every shadow
// ray carries the transmittance of the media it crosses.
#include "core/pt/path_tracer.h"

#include "core/scene/equiangular_choice.h"
#include "core/scene/media_step.h"
#include "core/media/equiangular.h"
#include "core/media/phase_function.h"
#include "core/sampling/mis.h"
#include "core/sampling/russian_roulette.h"

namespace pathlab {

PathTracer::PathTracer(const Scene& scene, const PathTracerOptions& options)
    : scene_(scene),
      maxLength_(options.maxLength),
      russianRoulette_(options.russianRoulette),
      mediumSampling_(options.mediumSampling) {}

namespace {

struct LightChoice {
  const Light* light = nullptr;
  int index = -1;
  float pmf = 0.f;
  LightLiSample ls;
};

// A light chosen for the receiver ctx (LightSet::sampleNee: by power, or a light BVH) and a point
// on it, seen from ctx.p.
std::optional<LightChoice> chooseLight(const Scene& scene, const LightSampleContext& ctx, Pcg32& rng) {
  const LightSet& lights = scene.lights();
  LightChoice c;
  const float uLight = rng.next1D();
  const Vec2 uPos = rng.next2D();
  const int li = lights.sampleNee(ctx, uLight, &c.pmf);
  if (li < 0 || c.pmf <= 0.f) return std::nullopt;
  c.index = li;
  c.light = &lights[static_cast<size_t>(li)];
  c.ls = c.light->sampleLi(ctx.p, uPos);
  if (c.ls.pdfW <= 0.f || isBlack(c.ls.Li)) return std::nullopt;
  return c;
}

// The transmittance of the shadow ray from (p, n, e), leaving in medium `medium`, to the light
// sample: 0 or 1 without media.
Spectrum shadowTransmittance(const Scene& scene, const LightChoice& c, const Vec3& p, const Vec3& n, const Vec3& e,
                             int medium) {
  const LightLiSample& ls = c.ls;
  if (scene.hasMedia())
    return c.light->isInfinite() ? scene.transmittanceToInfinity(p, n, e, ls.wi, medium)
                                 : scene.transmittance(p, n, e, ls.pLight, ls.nLight, ls.pError, medium);
  const bool unblocked = c.light->isInfinite() ? scene.visibleToInfinity(p, n, e, ls.wi)
                                               : scene.visible(p, n, e, ls.pLight, ls.nLight, ls.pError);
  return Spectrum(unblocked ? 1.f : 0.f);
}

}  // namespace

// One light sample for the vertex `hit`: the (s = 1) connection of the path tracer. Weighted
// against BSDF sampling of the same path with the power heuristic.
Spectrum PathTracer::sampleDirect(const SurfaceHit& hit, const Bsdf& bsdf, const Vec3& wo,
                                  Pcg32& rng, Counters& counters) const {
  const std::optional<LightChoice> c = chooseLight(scene_, LightSampleContext{hit.p, hit.ng}, rng);
  if (!c) return Spectrum(0.f);
  const LightLiSample& ls = c->ls;
  const BsdfEval ev = bsdf.eval(wo, ls.wi, TransportMode::Radiance);
  if (isBlack(ev.f)) return Spectrum(0.f);
  ++counters.shadowRays;
  const Spectrum T = shadowTransmittance(scene_, *c, hit.p, hit.ng, hit.pError, hit.media.toward(hit.ng, ls.wi));
  if (isBlack(T)) return Spectrum(0.f);
  const float pdfLight = c->pmf * ls.pdfW;
  const float weight = ls.isDelta ? 1.f : powerHeuristic(pdfLight, ev.pdfFwdW);
  return T * ev.f * ls.Li * (absDot(ls.wi, hit.ns) * weight / pdfLight);
}

// The last edge of a path whose last scattering vertex x lies in a medium, toward a point y on a
// light, has three techniques here (Kulla and Fajardo 2012, sec. 5):
//   A  distance sampling places x, next-event estimation chooses y from x   p_d(t) pmf(y | x) pdfW(y | x)
//   B  the light and y chosen from the segment's origin o, then equiangular   p_e(t | y) pmf(y | o) pdfW(y | x)
//      sampling places x toward y
//   C  distance sampling places x, phase sampling the direction to y         p_d(t) phase
// in one measure (the distance along the segment times the solid angle at x; an area light's
// points are uniform in area whatever the receiver, so pdfW(y | x) is the same in A and B). The
// weights below divide all three by p_d(t), the density of the vertex the path tracer continues
// from; they leave out Russian roulette, as pbrt's VolPathIntegrator does, and stay a partition of
// unity. C cannot reach a punctual light, B cannot aim at an infinite one nor place x past the
// first segment.
float PathTracer::equiangularRatio(const MediumVertexSegment& segment, int light, const Vec3& y) const {
  if (mediumSampling_ == MediumSampling::Distance || !segment.valid()) return 0.f;
  const LightSet& lights = scene_.lights();
  if (lights[static_cast<size_t>(light)].isInfinite()) return 0.f;
  const std::optional<EquiangularSegment> eq = equiangularSegment(segment.ray.o, segment.ray.d, segment.tMax, y);
  if (!eq) return 0.f;
  return equiangularPdf(*eq, segment.t) / segment.pdfDistance *
         lights.pmfNee(LightSampleContext{segment.ray.o, Vec3(0.f)}, light);
}

// Technique A: next-event estimation from a point in a medium. The phase function is both the
// "BSDF" and the density phase sampling would give the direction.
Spectrum PathTracer::sampleDirectInMedium(const Vec3& p, int medium, const Vec3& wo, const MediumVertexSegment& segment,
                                          Pcg32& rng, Counters& counters) const {
  const std::optional<LightChoice> c = chooseLight(scene_, LightSampleContext{p, Vec3(0.f)}, rng);
  if (!c) return Spectrum(0.f);
  const LightLiSample& ls = c->ls;
  const float pdfEquiangular = equiangularRatio(segment, c->index, ls.pLight) * ls.pdfW;
  const float pdfLight = nextEventDensity(c->pmf * ls.pdfW, pdfEquiangular);
  if (!(pdfLight > 0.f)) return Spectrum(0.f);  // left to B: no shadow ray
  const float phase = phaseHG(wo, ls.wi, scene_.medium(medium).g);
  ++counters.shadowRays;
  const Spectrum T = shadowTransmittance(scene_, *c, p, Vec3(0.f), Vec3(0.f), medium);
  if (isBlack(T)) return Spectrum(0.f);
  const float weight = powerHeuristic(pdfLight, pdfEquiangular, ls.isDelta ? 0.f : phase);
  return T * ls.Li * (phase * weight / pdfLight);
}

// Technique B. Its estimate of the edge o -> x -> y, with T_m and sigma_s of the segment's medium:
//   T_m(t) sigma_s phase T(x, y) Li(y -> x) / (pmf(y | o) pdfW(y | x) p_e(t | y)),
// Li / pdfW being Le G / pdfA for an area light and I / |x - y|^2 for a punctual one.
Spectrum PathTracer::sampleEquiangularDirect(const Ray& ray, int medium, float tMax, Pcg32& rng,
                                             Counters& counters) const {
  const HomogeneousMedium& m = scene_.medium(medium);
  const LightSet& lights = scene_.lights();
  // A light at infinity has no point to aim at: A and C take those paths.
  const std::optional<EquiangularChoice> choice = chooseEquiangularVertex(scene_, ray.o, ray.d, tMax, rng);
  if (!choice) return Spectrum(0.f);
  const int li = choice->light;
  const float pmf = choice->pmf, t = choice->t, pdfT = choice->pdfT, pdfDistance = distancePdf(m, t);
  if (!(pdfT > 0.f && pdfDistance > 0.f)) return Spectrum(0.f);
  const Vec3 x = ray.o + t * ray.d;
  const Light& light = lights[static_cast<size_t>(li)];
  const LightChoice c{&light, li, pmf, light.sampleLi(x, choice->uPos)};  // the same point, seen from x
  const LightLiSample& ls = c.ls;
  if (!(ls.pdfW > 0.f) || isBlack(ls.Li)) return Spectrum(0.f);
  const float phase = phaseHG(-ray.d, ls.wi, m.g);
  const float pdfEquiangular = pdfT / pdfDistance * pmf * ls.pdfW;
  const float pdfLight = nextEventDensity(lights.pmfNee(LightSampleContext{x, Vec3(0.f)}, li) * ls.pdfW, pdfEquiangular);
  const float weight = powerHeuristic(pdfEquiangular, pdfLight, ls.isDelta ? 0.f : phase);
  if (!(weight > 0.f)) return Spectrum(0.f);
  ++counters.shadowRays;
  const Spectrum T = shadowTransmittance(scene_, c, x, Vec3(0.f), Vec3(0.f), medium);
  if (isBlack(T)) return Spectrum(0.f);
  return m.transmittance(t) * m.sigmaS * T * ls.Li * (phase * weight / (pmf * ls.pdfW * pdfT));
}

// The environment seen by a ray that left the scene in direction w, weighted against next-event
// estimation's sampling of the same direction (power heuristic, as for area lights) from `prev`,
// the vertex the ray left.
Spectrum PathTracer::environmentSeen(const Vec3& w, bool prevDelta, float prevPdfW,
                                     const LightSampleContext& prev) const {
  const LightSet& lights = scene_.lights();
  const Light& light = lights[static_cast<size_t>(lights.environment())];
  const Spectrum Le = light.environmentLight()->Le(w);
  if (prevDelta || isBlack(Le)) return Le;
  const float pdfLight = lights.pmfNee(prev, lights.environment()) * light.environmentLight()->pdfDirection(w);
  return Le * powerHeuristic(prevPdfW, pdfLight);
}

Spectrum PathTracer::Li(const Ray& cameraRay, Pcg32& rng, Counters& counters, int medium) const {
  Spectrum L(0.f), beta(1.f);
  Ray ray = cameraRay;
  bool prevDelta = true;  // the camera vertex: emitters seen directly get weight one
  float prevPdfW = 0.f;
  // The vertex the ray left, as next-event estimation there saw it (the receiver of its light choice).
  LightSampleContext prev{ray.o, Vec3(0.f)};
  // Where the last vertex lies on its ray, when it is a medium vertex (technique C's weight).
  MediumVertexSegment prevSegment;
  const bool equiangular = mediumSampling_ != MediumSampling::Distance && scene_.hasMedia();
  RussianRoulette roulette(beta, RouletteCount::NonDeltaScatterings);
  auto survivesRoulette = [&](bool delta) {
    return !russianRoulette_ || roulette.survives(beta, delta, rng);
  };
  for (int edges = 1;; ++edges) {
    const MediaStep step = traceStep(scene_, ray, medium, rng, counters);
    // Technique B on this edge's first segment: its vertex would be the path's edges-th, then an
    // edge to the light.
    // Not in a heterogeneous medium: the weights need distance sampling's density there, which
    // delta tracking does not give in closed form (volume_grid.h).
    if (equiangular && medium >= 0 && edges < maxLength_ && scene_.medium(medium).scatters() &&
        !scene_.mediumGrid(medium))
      L += beta * sampleEquiangularDirect(ray, medium, step.firstSegment, rng, counters);
    beta *= step.weight;  // one in vacuum
    if (step.kind == MediaStepKind::Absorbed) break;
    if (step.kind == MediaStepKind::Medium) {
      // A scattering point: NEE, then the phase function samples the next direction. Its value
      // over its density is one, so the throughput is unchanged (sigma_s T / pdf is in weight).
      if (edges >= maxLength_) break;
      MediumVertexSegment segment;
      if (equiangular && step.firstSegmentT >= 0.f && !scene_.mediumGrid(medium))
        segment = {ray, step.firstSegment, step.firstSegmentT, distancePdf(scene_.medium(medium), step.firstSegmentT)};
      // The step may have crossed index-matched boundaries into another medium.
      medium = step.medium;
      const Vec3 wo = -ray.d;
      L += beta * sampleDirectInMedium(step.p, medium, wo, segment, rng, counters);
      const float g = scene_.medium(step.medium).g;
      const Vec3 wi = samplePhaseHG(wo, g, rng.next2D());
      prevDelta = false;
      prevPdfW = phaseHG(wo, wi, g);
      prev = LightSampleContext{step.p, Vec3(0.f)};
      prevSegment = segment;
      ray = Ray{step.p, wi};
      if (!survivesRoulette(false)) break;
      continue;
    }
    const std::optional<SurfaceHit>& hit = step.hit;  // empty when the ray escaped
    if (!hit) {
      if (scene_.lights().environment() >= 0) L += beta * environmentSeen(ray.d, prevDelta, prevPdfW, prev);
      break;
    }
    const Vec3 wo = -ray.d;

    if (hit->light >= 0) {
      const Light& light = scene_.lights()[static_cast<size_t>(hit->light)];
      const Spectrum Le = light.radiance(hit->ng, scene_.emissionUv(hit->material, hit->uv, hit->uv1), wo);
      if (!isBlack(Le)) {
        float weight = 1.f;
        if (!prevDelta) {
          const float pdfW = light.pdfLi(prev.p, hit->p, hit->ng);
          const float pdfEquiangular = equiangularRatio(prevSegment, hit->light, hit->p) * pdfW;
          const float pdfLight = nextEventDensity(scene_.lights().pmfNee(prev, hit->light) * pdfW, pdfEquiangular);
          weight = powerHeuristic(prevPdfW, pdfLight, pdfEquiangular);
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
    prev = LightSampleContext{hit->p, hit->ng};
    prevSegment = {};
    ray = Ray{offsetRayOrigin(hit->p, hit->pError, hit->ng, bs->wi), bs->wi};
    medium = hit->media.toward(hit->ng, bs->wi);

    if (!survivesRoulette(bs->isDelta)) break;
  }
  return L;
}

}  // namespace pathlab
