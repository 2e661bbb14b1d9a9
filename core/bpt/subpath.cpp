// Subpath generation: the camera and light random walks of bidirectional path tracing.
#include "core/bpt/subpath.h"

#include "core/bsdf/bsdf.h"
#include "core/scene/media_step.h"
#include "core/media/phase_function.h"
#include "core/sampling/russian_roulette.h"

namespace pathlab {

namespace {

// A camera ray that leaves the scene ends on the environment (pbrt-v4 RandomWalk's escaped ray):
// a light vertex at infinity in direction ray.d, far along it from `prev`.
void setEnvironmentVertex(const Scene& scene, const Ray& ray, const PathVertex& prev, int light, PathVertex& v) {
  v = PathVertex{};
  v.type = VertexType::Light;
  v.light = light;
  v.isInfinite = true;
  v.ng = -ray.d;  // the direction light travels
  v.wo = -ray.d;
  v.p = prev.p + ray.d * (2.f * scene.bounds().radius);
}

// pbrt-v4 RandomWalk: extends `path` from its last vertex along `ray`. `pdfFwdW` is the density
// (solid angle, or planar area from a light at infinity) with which `ray.d` was chosen. Each new
// vertex gets pdfFwdA; each sampled direction fills in pdfRevA of the vertex before it. A camera
// walk whose ray escapes ends on the environment light, when the scene has one. In a scene with
// media the ray starts in `medium`; the distance to the next vertex is sampled in every medium it
// crosses (media_step.h), and a scattering point in a medium becomes a Medium vertex whose
// densities, in the volume measure, have no cosine (convertDensity) and whose direction the phase
// function samples. The distance sampling's own probabilities stay out of pdfFwdA / pdfRevA, as
// Russian roulette's do: every technique's density omits the same factors, so the MIS weights
// remain a partition of unity (pbrt-v3's BDPT does the same).
template <class Rng>
void randomWalk(const Scene& scene, Ray ray, Spectrum beta, float pdfFwdW, TransportMode mode, Rng& rng,
                const WalkOptions& options, Subpath& path, Counters& counters, int medium) {
  RussianRoulette roulette(beta, mode == TransportMode::Radiance ? RouletteCount::NonDeltaScatterings
                                                                : RouletteCount::Scatterings);
  bool delta = false;  // the last scattering was a delta lobe
  float deltaFactor = 1.f;  // the delta lobes' choice factor so far (PathVertex::omittedFactor)
  const Bsdf* prevBsdf = nullptr;  // the BSDF that chose `ray`, when a surface vertex did (non-delta)
  float prevPhaseG = 0.f;          // the anisotropy of the phase function that chose `ray`...
  bool prevPhase = false;          // ...when a medium vertex did
  const int environment = mode == TransportMode::Radiance ? scene.lights().environment() : -1;
  // Both densities at prev of the direction pair (prev.wo, dir), from the scattering that chose
  // dir there; false when no scattering at prev did (an origin vertex, or a delta lobe).
  auto prevDensities = [&](const PathVertex& prev, const Vec3& dir, BsdfDensities& ev) {
    if (prevBsdf) {
      ev = prevBsdf->densities(prev.wo, dir);
      return true;
    }
    if (prevPhase) {
      ev.pdfFwdW = ev.pdfRevW = phaseHG(prev.wo, dir, prevPhaseG);  // symmetric
      return true;
    }
    return false;
  };
  if (options.recordRays && path.rays.size() < static_cast<size_t>(options.maxVertices))
    path.rays.resize(static_cast<size_t>(options.maxVertices));
  path.rayCount = 0;
  while (path.count < options.maxVertices) {
    const MediaStep step = traceStep(scene, ray, medium, rng, counters);
    if (options.recordRays) {
      // The ray from the last vertex: one per vertex, in order (nothing shoots two).
      path.rays[static_cast<size_t>(path.count - 1)] = WalkRay{ray.d, beta, pdfFwdW, step.firstSegment, medium};
      path.rayCount = path.count;
    }
    beta *= step.weight;  // one in vacuum
    if (step.kind == MediaStepKind::Absorbed) break;
    const bool inMedium = step.kind == MediaStepKind::Medium;
    const Vec3& mediumPoint = step.p;
    // The step may have crossed index-matched boundaries: a scattering point lies in the medium
    // the step ended in, not necessarily the one the ray started in.
    if (inMedium) medium = step.medium;
    const std::optional<SurfaceHit>& hit = step.hit;
    if (!hit && !inMedium && environment < 0) break;
    PathVertex& prev = path[path.count - 1];
    PathVertex& v = path[path.count];
    if (!hit && !inMedium) {
      setEnvironmentVertex(scene, ray, prev, environment, v);
      v.beta = beta;
      v.omittedFactor = roulette.weight() * deltaFactor;
      BsdfDensities ev;
      if (prevDensities(prev, ray.d, ev)) {
        pdfFwdW = ev.pdfFwdW;
        PathVertex& prevPrev = path[path.count - 2];
        prevPrev.pdfRevA = convertDensity(ev.pdfRevW, prev, prevPrev);
      }
      v.pdfFwdA = convertDensity(pdfFwdW, prev, v);  // a solid angle: v is at infinity
      v.areaToPrev = convertDensity(1.f, v, prev);
      ++path.count;
      break;
    }
    v = PathVertex{};
    if (inMedium) {
      v.type = VertexType::Medium;
      v.p = mediumPoint;
      v.media = MediumInterface{static_cast<int16_t>(medium), static_cast<int16_t>(medium)};
    } else {
      v.type = VertexType::Surface;
      v.p = hit->p;
      v.pError = hit->pError;
      v.ng = hit->ng;
      v.ns = hit->ns;
      v.uv = hit->uv;
      v.uv1 = hit->uv1;
      v.color = hit->color;
      v.material = hit->material;
      v.light = hit->light;
      v.media = hit->media;
    }
    // From the stored positions, not the (offset) ray: the densities below are then those of
    // the path the vertices describe, which is what misWeight re-evaluates.
    const Vec3 back = prev.p - v.p;
    v.wo = glm::dot(back, back) > 0.f && !prev.isInfinite ? glm::normalize(back) : -ray.d;
    v.beta = beta;
    v.omittedFactor = roulette.weight() * deltaFactor;
    const Vec3 dirGeom = -v.wo;
    BsdfDensities ev;
    if (prevDensities(prev, dirGeom, ev)) {
      // Re-evaluate both densities of the sampled scattering at prev along the directions between
      // the stored points (the ray left from an offset origin; near-coincident vertices would
      // otherwise disagree with misWeight's own evaluation). Densities only: the value f of this
      // pair is never used, and computing it cost as much as the densities.
      pdfFwdW = ev.pdfFwdW;
      PathVertex& prevPrev = path[path.count - 2];
      prevPrev.pdfRevA = convertDensity(ev.pdfRevW, prev, prevPrev);
    } else if (prev.type == VertexType::Light && prev.onSurface()) {
      pdfFwdW = scene.lights()[static_cast<size_t>(prev.light)].pdfLe(prev.p, prev.ng, dirGeom).pdfDirW;
    }
    v.pdfFwdA = convertDensity(pdfFwdW, prev, v);
    v.areaToPrev = convertDensity(1.f, v, prev);

    if (inMedium) {
      ++path.count;
      if (path.count >= options.maxVertices) break;
      // The phase function samples the next direction exactly (value over density one): the
      // throughput is unchanged; sigma_s T / pdf is already in beta.
      prevPhaseG = scene.medium(medium).g;
      const Vec3 wi = samplePhaseHG(v.wo, prevPhaseG, rng.next2D());
      pdfFwdW = phaseHG(v.wo, wi, prevPhaseG);
      prevBsdf = nullptr;
      prevPhase = true;
      prev.pdfRevA = convertDensity(pdfFwdW, v, prev);
      ray = Ray{v.p, wi};
      delta = false;
    } else {
      // Every surface vertex, the last included, gets its BSDF: connect() evaluates it.
      Bsdf& bsdf = path.bsdfs[static_cast<size_t>(path.count)];
      bsdf = scene.bsdf(v.material, ShadingInputs{v.uv, v.uv1, v.color}, v.ns, v.ng);
      ++path.count;
      if (path.count >= options.maxVertices) break;

      const float uLobe = rng.next1D();
      const Vec2 uDir = rng.next2D();
      const std::optional<BsdfSample> bs = bsdf.sample(v.wo, uDir, uLobe, mode);
      if (!bs || bs->pdfFwdW <= 0.f || isBlack(bs->f)) break;
      // In Importance mode f is the adjoint BSDF with Veach's shading-normal correction (bsdf.h).
      beta *= bs->f * (absDot(bs->wi, v.ns) / bs->pdfFwdW);
      pdfFwdW = bs->pdfFwdW;
      float pdfRevW = bs->pdfRevW;
      prevBsdf = nullptr;
      prevPhase = false;
      delta = bs->isDelta;
      if (bs->isDelta) {
        // pbrt: a delta vertex stores zero densities, remapped to one where ratios are formed; the
        // lobe's choice probability, in beta, is then left out of them. Relative to the camera
        // side's choice of the same lobe (PathVertex::omittedFactor): a light walk's factor is the
        // camera side's probability over its own, one where the lobes are chosen alike both ways.
        if (mode == TransportMode::Importance) deltaFactor *= bs->pdfRevW / bs->pdfFwdW;
        v.isDelta = true;
        pdfFwdW = pdfRevW = 0.f;
      } else {
        prevBsdf = &bsdf;
      }
      prev.pdfRevA = convertDensity(pdfRevW, v, prev);
      ray = Ray{offsetRayOrigin(v.p, v.pError, v.ng, bs->wi), bs->wi};
      medium = v.media.toward(v.ng, bs->wi);
    }

    // Russian roulette as in the path tracer (russian_roulette.h). Unbiased; the MIS densities
    // leave it out, which keeps the weights a partition of unity.
    if (options.russianRoulette && !roulette.survives(beta, delta, rng)) break;
  }
}

}  // namespace

template <class Rng>
int generateCameraSubpath(const Scene& scene, const Camera& camera, Vec2 pRaster, Vec2 uLens, Rng& rng,
                          const WalkOptions& options, CameraSubpath& path, Counters& counters) {
  path.setCapacity(options.maxVertices);
  path.count = 0;
  path.rayCount = 0;  // no ray recorded until the walk shoots one (the walks reuse their buffers)
  if (options.maxVertices < 1) return 0;
  const Ray ray = camera.generateRay(pRaster, uLens);
  const CameraPdf pdf = camera.pdfWe(ray);
  PathVertex& c = path[0];
  c = PathVertex{};
  c.type = VertexType::Camera;
  c.p = ray.o;
  // We / (pdfPosA pdfDirW) = 1 per pixel sample with the box filter (camera.h).
  c.beta = Spectrum(1.f);
  c.pdfFwdA = pdf.pdfPosA;
  c.isDeltaPosition = camera.isPinhole();
  c.media = MediumInterface{static_cast<int16_t>(options.cameraMedium), static_cast<int16_t>(options.cameraMedium)};
  path.count = 1;
  if (!(pdf.pdfDirW > 0.f) || !(pdf.pdfPosA > 0.f)) return path.count;
  float walkPdf = pdf.pdfDirW;
  if (camera.isOrthographic()) {
    // The adjoint of a directional light: the direction is a delta (the vertex cannot be
    // connected to: isDelta rules out t = 1), the position on the film is what is sampled, and
    // x1's area density is that planar density times its cosine (PathVertex::isInfinite, ng the
    // direction importance travels: convertDensity).
    c.isDelta = true;
    c.isInfinite = true;
    c.ng = ray.d;
    c.pdfFwdA = pdf.pdfDirW;
    walkPdf = pdf.pdfPosA;
  }
  randomWalk(scene, ray, Spectrum(1.f), walkPdf, TransportMode::Radiance, rng, options, path, counters,
             options.cameraMedium);
  return path.count;
}

template <class Rng>
int generateLightSubpath(const Scene& scene, Rng& rng, const WalkOptions& options, LightSubpath& path,
                         Counters& counters) {
  path.setCapacity(options.maxVertices);
  path.count = 0;
  if (options.maxVertices < 1) return 0;
  const LightSet& lights = scene.lights();
  float pmf = 0.f;
  const float uLight = rng.next1D();
  const Vec2 uPos = rng.next2D(), uDir = rng.next2D();
  const int li = lights.sample(uLight, &pmf);
  if (li < 0 || !(pmf > 0.f)) return 0;
  const Light& light = lights[static_cast<size_t>(li)];
  const LightLeSample le = light.sampleLe(uPos, uDir);
  if (!(le.pdfPosA > 0.f) || !(le.pdfDirW > 0.f) || isBlack(le.Le)) return 0;

  PathVertex& x0 = path[0];
  x0 = PathVertex{};
  x0.type = VertexType::Light;
  x0.p = le.ray.o;
  x0.pError = le.pError;
  // Where a connection from x0 reads the emitter's radiance again (emittedOverOriginPdf): a
  // textured emitter's radiance varies over the triangle.
  x0.uv = le.uv;
  x0.ng = light.type() == LightType::Area || light.isInfinite() ? le.n : Vec3(0.f);
  x0.light = li;
  x0.isDeltaPosition = light.isDeltaPosition();
  x0.isDeltaDirection = light.isDeltaDirection();
  x0.isInfinite = light.isInfinite();
  x0.media = scene.lightMedia(li);
  // The origin of a light at infinity is its direction, chosen with the light (a directional
  // light's is a delta: density one, remapped); the disk position density moves to x1, in area
  // measure there (pbrt-v4 GenerateLightSubpath).
  x0.pdfFwdA = x0.isInfinite ? pmf * le.pdfDirW : pmf * le.pdfPosA;
  x0.beta = le.Le / (pmf * le.pdfPosA);
  path.count = 1;

  const float cosLight = light.type() == LightType::Area ? absDot(le.n, le.ray.d) : 1.f;
  const Spectrum beta = le.Le * (cosLight / (pmf * le.pdfPosA * le.pdfDirW));
  const Ray ray{offsetRayOrigin(le.ray.o, le.pError, le.n, le.ray.d), le.ray.d};
  const float pdfW = x0.isInfinite ? le.pdfPosA : le.pdfDirW;
  randomWalk(scene, ray, beta, pdfW, TransportMode::Importance, rng, options, path, counters,
             mediumToward(x0, le.ray.d));
  // x0's density were next-event estimation to choose it for x1 (technique s = 1 of the paths
  // through x0 and x1): the same position or direction density, the receiver's light choice.
  PathVertex& origin = path[0];
  origin.pdfNeeA = origin.pdfFwdA;
  if (lights.neeByContext() && path.count >= 2) {
    const float pmfNee = lights.pmfNee(neeContext(path[1]), li);
    origin.pdfNeeA = origin.isInfinite ? pmfNee * le.pdfDirW : pmfNee * le.pdfPosA;
  }
  return path.count;
}

#define PATHLAB_WALKS(Rng)                                                                                           \
  template int generateCameraSubpath(const Scene&, const Camera&, Vec2, Vec2, Rng&, const WalkOptions&,            \
                                     CameraSubpath&, Counters&);                                                    \
  template int generateLightSubpath(const Scene&, Rng&, const WalkOptions&, LightSubpath&, Counters&);
PATHLAB_WALKS(Pcg32)
PATHLAB_WALKS(PrimarySampleStream)
#undef PATHLAB_WALKS

}  // namespace pathlab
