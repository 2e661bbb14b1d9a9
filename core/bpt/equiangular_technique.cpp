// The equiangular technique E(1, k): its density factor and its sample.
#include "core/bpt/equiangular_technique.h"

#include "core/media/equiangular.h"
#include "core/scene/equiangular_choice.h"
#include "core/media/phase_function.h"

#include <limits>

namespace pathlab {

namespace {
constexpr float kUnbounded = std::numeric_limits<float>::infinity();

// The medium E places vertices in when a ray starts in m: homogeneous and scattering.
bool equiangularMedium(const Scene& scene, int m) {
  return m >= 0 && !scene.mediumGrid(m) && scene.medium(m).scatters();
}
}  // namespace

bool hasEquiangularMedium(const Scene& scene) {
  const int n = static_cast<int>(scene.media().media().size());
  for (int m = 0; m < n; ++m)
    if (equiangularMedium(scene, m)) return true;
  return false;
}

bool equiangularFamilySampled(const Scene& scene, const BidirOptions& options) {
  const bool anyMerge = covers(options.techniques.families(), TechniqueKind::Merge) ||
                        (options.isolate && options.isolate->kind == TechniqueKind::Merge);
  return options.mis.mediumSampling != MediumSampling::Distance && !anyMerge &&
         options.connect == ConnectStrategy::All && hasEquiangularMedium(scene);
}

double equiangularFactor(const Scene& scene, const PathVertex& x0, const PathVertex& x1, const PathVertex& x2) {
  if (x1.type != VertexType::Medium || x0.light < 0 || x0.isInfinite) return 0.0;
  const int m = x1.media.inside;
  if (!equiangularMedium(scene, m)) return 0.0;
  const Vec3 e = x1.p - x2.p;
  const float length = glm::length(e);
  if (!(length > 0.f)) return 0.0;
  const Vec3 d = e / length;
  if (mediumToward(x2, d) != m) return 0.0;
  const std::optional<EquiangularSegment> eq = equiangularSegment(x2.p, d, kUnbounded, x0.p);
  if (!eq) return 0.0;
  const double pe = equiangularPdf(*eq, length), pd = distancePdf(scene.medium(m), length);
  if (!(pe > 0.0 && pd > 0.0)) return 0.0;
  double f = pe / pd;
  const LightSet& lights = scene.lights();
  if (lights.neeByContext()) {
    // x0's light chosen with x2 as the receiver, where the light subpaths choose it by power.
    const double pmfPower = lights.pmf(x0.light);
    if (!(pmfPower > 0.0)) return 0.0;
    f *= lights.pmfNee(LightSampleContext{x2.p, Vec3(0.f)}, x0.light) / pmfPower;
  }
  return f;
}

bool formEquiangularConnection(const Scene& scene, const Subpath& cameraPath, int t, Pcg32& rng, PathVertex& x,
                               Connection& c, Counters& counters) {
  c.hasSampled = false;
  c.pdfs.atLight = c.pdfs.atCamera = c.pdfs.atLens = false;
  if (t < 2 || t - 2 >= cameraPath.rayCount) return false;
  const WalkRay& ray = cameraPath.rays[static_cast<size_t>(t - 2)];
  const PathVertex& o = cameraPath[t - 2];
  const int m = ray.medium;
  if (!equiangularMedium(scene, m)) return false;
  const HomogeneousMedium& medium = scene.medium(m);

  // The light and its point, chosen with o as the receiver (x does not exist yet), then x on the
  // unbounded ray from o (equiangularFactor's density), past its first surface only where the
  // medium goes on (an index-matched boundary). A light at infinity: C(1, t) keeps those paths.
  const LightSet& lights = scene.lights();
  const std::optional<EquiangularChoice> choice = chooseEquiangularVertex(scene, o.p, ray.d, kUnbounded, rng);
  if (!choice) return false;
  const int li = choice->light;
  const float pmf = choice->pmf, tx = choice->t, pdfT = choice->pdfT;
  if (!(tx > 0.f && pdfT > 0.f) || !std::isfinite(tx)) return false;
  const Light& light = lights[static_cast<size_t>(li)];
  const Vec3 p = o.p + tx * ray.d;
  Spectrum T;
  if (tx <= ray.firstSegment) {
    T = medium.transmittance(tx);  // one medium all the way: the closed form
  } else {
    if (scene.mediumAt(p) != m) return false;
    ++counters.shadowRays;
    T = scene.transmittance(o.p, o.type == VertexType::Surface ? o.ng : Vec3(0.f), o.pError, p, Vec3(0.f),
                            Vec3(0.f), m);
  }
  if (isBlack(T)) return false;

  x = PathVertex{};
  x.type = VertexType::Medium;
  x.p = p;
  x.media = MediumInterface{static_cast<int16_t>(m), static_cast<int16_t>(m)};
  const Vec3 back = o.p - p;
  x.wo = glm::dot(back, back) > 0.f ? glm::normalize(back) : -ray.d;
  // The camera subpath's throughput at x: T sigma_s over the density that placed x, where
  // distance sampling's vertex has sigma_s T / p_d.
  x.beta = ray.beta * T * medium.sigmaS / pdfT;
  // Its densities as the walk gives z(t-1) (randomWalk): the direction's density at o, in the
  // volume measure; the distance's probability left out as there.
  x.pdfFwdA = convertDensity(ray.pdfFwdW, o, x);
  x.areaToPrev = convertDensity(1.f, x, o);

  // The connection to the light point, as formConnection's s = 1 with x as pt.
  const LightLiSample ls = light.sampleLi(p, choice->uPos);  // the same point, seen from x
  if (!(ls.pdfW > 0.f) || isBlack(ls.Li)) return false;
  const BsdfEval ev = phaseEval(scene, x, ls.wi);
  c.pdfs.atCamera = true;
  c.pdfs.ptToQs = ev.pdfFwdW;
  c.pdfs.ptToPrev = ev.pdfRevW;
  // The light point's density is pmf(light | o) times its area (or position) density, which is
  // pmf * pdfW seen from x.
  c.L = x.beta * ev.f * ls.Li / (pmf * ls.pdfW);
  if (isBlack(c.L)) return false;
  c.shadowRay.between(p, Vec3(0.f), Vec3(0.f), ls.pLight, ls.nLight, ls.pError);
  c.shadowRay.medium = m;
  c.edgeLength2 = glm::dot(p - ls.pLight, p - ls.pLight);
  // As formConnection's light sample: the origin's density chosen by power (the techniques
  // s' >= 2) and by next-event estimation for x (C(1, t)); the weights form E's own from these.
  setLightSampleVertex(scene, li, ls, lights.pmfNee(LightSampleContext{p, Vec3(0.f)}, li), lights.pmf(li), pmf,
                       c.sampled);
  c.hasSampled = true;
  return true;
}

}  // namespace pathlab
