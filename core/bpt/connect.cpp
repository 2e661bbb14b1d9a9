// Connection of a light subpath prefix (s vertices) with a camera subpath prefix (t vertices).
#include "core/bpt/connect.h"

#include "core/bsdf/bsdf.h"
#include "core/media/phase_function.h"

#include <limits>

namespace pathlab {

Spectrum emittedOverOriginPdf(const Scene& scene, const PathVertex& x0, const Vec3& w) {
  const Light& light = scene.lights()[static_cast<size_t>(x0.light)];
  const float pmf = scene.lights().pmf(x0.light);
  if (!(pmf > 0.f)) return Spectrum(0.f);
  switch (light.type()) {
    case LightType::Area: {
      // Lambertian emitter: x0.beta = Le / (pmf pdfPosA) on whichever side it emits.
      if (isBlack(light.radiance(x0.ng, x0.uv, w))) return Spectrum(0.f);
      return x0.beta;
    }
    case LightType::Point:
    case LightType::Spot:
      return light.intensity(w) / pmf;  // position density 1
    case LightType::Directional:
    case LightType::Environment:
      return Spectrum(0.f);  // at infinity: never met by a connection
  }
  return Spectrum(0.f);
}

bool unoccluded(const Scene& scene, const ShadowRay& r) {
  return r.toInfinity ? scene.visibleToInfinity(r.a, r.na, r.ea, r.direction)
                      : scene.visible(r.a, r.na, r.ea, r.b, r.nb, r.eb);
}

Spectrum transmittance(const Scene& scene, const ShadowRay& r) {
  return r.toInfinity ? scene.transmittanceToInfinity(r.a, r.na, r.ea, r.direction, r.medium)
                      : scene.transmittance(r.a, r.na, r.ea, r.b, r.nb, r.eb, r.medium);
}

void setLightSampleVertex(const Scene& scene, int li, const LightLiSample& ls, float pmfNee, float pmfPower,
                          float pmfChosen, PathVertex& v) {
  const Light& light = scene.lights()[static_cast<size_t>(li)];
  v = PathVertex{};
  v.type = VertexType::Light;
  v.p = ls.pLight;
  v.pError = ls.pError;
  v.uv = ls.uv;
  v.light = li;
  v.isDeltaPosition = light.isDeltaPosition();
  v.isDeltaDirection = light.isDeltaDirection();
  v.isInfinite = light.isInfinite();
  v.media = scene.lightMedia(li);
  v.ng = light.type() == LightType::Area ? ls.nLight : (v.isInfinite ? -ls.wi : Vec3(0.f));
  const EmissionPdf e = light.pdfLe(v.p, v.ng, -ls.wi);
  v.pdfNeeA = v.isInfinite ? pmfNee * e.pdfDirW : pmfNee * e.pdfPosA;
  v.pdfFwdA = v.isInfinite ? pmfPower * e.pdfDirW : pmfPower * e.pdfPosA;
  v.beta = ls.Li / (pmfChosen * ls.pdfW);
}

template <class Rng>
bool formConnection(const Scene& scene, const Camera& camera, const Subpath& lightPath, int s, const Subpath& cameraPath,
                    int t, Rng& rng, Connection& c) {
  c.hasSampled = false;
  c.pdfs.atLight = c.pdfs.atCamera = c.pdfs.atLens = false;
  if (t < 1 || s < 0) return false;

  if (s == 0) {
    // The camera subpath found an emitter by itself (Veach's s = 0).
    const PathVertex& pt = cameraPath[t - 1];
    if (t < 2 || pt.light < 0) return false;
    const Light& light = scene.lights()[static_cast<size_t>(pt.light)];
    if (pt.type == VertexType::Light) {
      // The walk escaped to the environment, which it sees in direction -wo.
      c.L = pt.beta * light.environmentLight()->Le(-pt.wo);
      return !isBlack(c.L);
    }
    if (pt.type != VertexType::Surface) return false;
    c.L = pt.beta * light.radiance(pt.ng, scene.emissionUv(pt.material, pt.uv, pt.uv1), pt.wo);
    return !isBlack(c.L);
  }

  if (t == 1) {
    // Light tracing: the lens point is sampled afresh from the light vertex.
    const PathVertex& qs = lightPath[s - 1];
    if (qs.isDelta || qs.isInfinite) return false;
    const std::optional<CameraWiSample> cs = camera.sampleWi(qs.p, rng.next2D());
    if (!cs) return false;
    Spectrum L;
    if (qs.type == VertexType::Light) {
      L = emittedOverOriginPdf(scene, qs, cs->wi) * (qs.onSurface() ? absDot(qs.ng, cs->wi) : 1.f);
    } else {
      const bool medium = qs.type == VertexType::Medium;
      const BsdfEval ev = medium ? phaseEval(scene, qs, cs->wi)
                                 : lightPath.bsdf(s - 1).eval(qs.wo, cs->wi, TransportMode::Importance);
      L = qs.beta * ev.f * (medium ? 1.f : absDot(cs->wi, qs.ns));
      c.pdfs.atLight = true;
      c.pdfs.qsToPt = ev.pdfFwdW;
      c.pdfs.qsToPrev = ev.pdfRevW;
    }
    if (isBlack(L)) return false;
    c.shadowRay.between(qs.p, qs.onSurface() ? qs.ng : Vec3(0.f), qs.pError, cs->pLens, Vec3(0.f), Vec3(0.f));
    c.edgeLength2 = glm::dot(cs->pLens - qs.p, cs->pLens - qs.p);  // qs is not at infinity (above)
    c.shadowRay.medium = mediumToward(qs, cs->wi);
    c.L = L * cs->We / cs->pdfW;
    c.pRaster = cs->pRaster;
    c.pdfs.atLens = true;
    c.pdfs.lensToQs = cs->pdfDirW;
    PathVertex& v = c.sampled;
    v = PathVertex{};
    v.type = VertexType::Camera;
    v.p = cs->pLens;
    v.beta = cs->We / cs->pdfW;
    v.isDeltaPosition = camera.isPinhole();
    // The camera's medium, as the walk's lens vertex has it: the equiangular technique's weights
    // ask in which medium a ray from the lens starts (equiangular_technique.h).
    if (cameraPath.count > 0) v.media = cameraPath[0].media;
    c.hasSampled = true;
    return true;
  }

  const PathVertex& pt = cameraPath[t - 1];
  const bool ptMedium = pt.type == VertexType::Medium;
  if (pt.isDelta || (pt.type != VertexType::Surface && !ptMedium)) return false;

  if (s == 1) {
    // Next-event estimation: a fresh light sample instead of the light subpath's x0. The density
    // divided by is pmf x sampleLi's pdf; for every light type pathlab has, that is the density
    // pmf x pdfLe().pdfPosA (uniform on the triangle, or a delta), at infinity pmf x
    // pdfLe().pdfDirW (the environment's direction density, a directional light's delta): the
    // `sampled.pdfNeeA` misWeight uses for this technique. The light is chosen for pt
    // (LightSet::sampleNee); `sampled.pdfFwdA` is the same vertex's density as a light subpath's
    // origin, chosen by power, which the techniques with s' >= 2 would give it.
    float pmf = 0.f;
    const float uLight = rng.next1D();
    const Vec2 uPos = rng.next2D();
    const LightSet& lights = scene.lights();
    const int li = lights.sampleNee(neeContext(pt), uLight, &pmf);
    if (li < 0 || !(pmf > 0.f)) return false;
    const Light& light = scene.lights()[static_cast<size_t>(li)];
    const LightLiSample ls = light.sampleLi(pt.p, uPos);
    if (!(ls.pdfW > 0.f) || isBlack(ls.Li)) return false;
    const BsdfEval ev = ptMedium ? phaseEval(scene, pt, ls.wi)
                                 : cameraPath.bsdf(t - 1).eval(pt.wo, ls.wi, TransportMode::Radiance);
    c.pdfs.atCamera = true;
    c.pdfs.ptToQs = ev.pdfFwdW;
    c.pdfs.ptToPrev = ev.pdfRevW;
    c.L = pt.beta * ev.f * ls.Li * ((ptMedium ? 1.f : absDot(ls.wi, pt.ns)) / (pmf * ls.pdfW));
    if (isBlack(c.L)) return false;
    if (light.isInfinite()) {
      c.shadowRay.toward(pt.p, pt.ng, pt.pError, ls.wi);
      c.edgeLength2 = std::numeric_limits<float>::infinity();
    } else {
      c.shadowRay.between(pt.p, pt.ng, pt.pError, ls.pLight, ls.nLight, ls.pError);
      c.edgeLength2 = glm::dot(pt.p - ls.pLight, pt.p - ls.pLight);
    }
    c.shadowRay.medium = mediumToward(pt, ls.wi);
    const float pmfPower = lights.neeByContext() ? lights.pmf(li) : pmf;
    setLightSampleVertex(scene, li, ls, pmf, pmfPower, pmf, c.sampled);
    c.hasSampled = true;
    return true;
  }

  return formInteriorConnection(scene, lightPath, s, cameraPath, t, c);
}

template bool formConnection(const Scene&, const Camera&, const Subpath&, int, const Subpath&, int, Pcg32&, Connection&);
template bool formConnection(const Scene&, const Camera&, const Subpath&, int, const Subpath&, int, PrimarySampleStream&,
                             Connection&);

Connection connect(const Scene& scene, const Camera& camera, const Subpath& lightPath, int s,
                   const Subpath& cameraPath, int t, Pcg32& rng, Counters& counters) {
  Connection c;
  if (!formConnection(scene, camera, lightPath, s, cameraPath, t, rng, c)) {
    c.L = Spectrum(0.f);
    return c;
  }
  if (needsShadowRay(s)) {
    ++counters.shadowRays;
    if (scene.hasMedia()) c.L *= transmittance(scene, c.shadowRay);
    else if (!unoccluded(scene, c.shadowRay)) c.L = Spectrum(0.f);
  }
  return c;
}

}  // namespace pathlab
