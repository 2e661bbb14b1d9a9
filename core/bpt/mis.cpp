// misWeight: copy the densities of the path, patch the four the connection changes, and walk the
// ratios p_i / p_s outward from the connection (Veach 1997, sec. 10.3).
#include "core/bpt/mis.h"

#include "core/bpt/equiangular_technique.h"
#include "core/bpt/light_paths.h"
#include "core/bsdf/bsdf.h"
#include "core/media/phase_function.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab {

namespace {

// Area density at `next` of being sampled from light vertex (or emitting surface) `v`.
float pdfLightToward(const Scene& scene, const PathVertex& v, const PathVertex& next) {
  if (v.light < 0) return 0.f;
  const Light& light = scene.lights()[static_cast<size_t>(v.light)];
  const EmissionPdf e = light.pdfLe(v.p, v.ng, glm::normalize(next.p - v.p));
  return convertDensity(v.isInfinite ? e.pdfPosA : e.pdfDirW, v, next);
}

// Density of x0 = v as the origin of a light subpath: pmf x pdfPosA; at infinity pmf x the
// density of its direction (pbrt-v4 PdfLightOrigin, InfiniteLightDensity): the disk's position
// density belongs to x1. A directional light's delta direction counts as one.
float pdfLightOrigin(const Scene& scene, const PathVertex& v, float pmf) {
  if (v.light < 0) return 0.f;
  const Light& light = scene.lights()[static_cast<size_t>(v.light)];
  if (light.isInfinite()) return pmf * light.pdfLe(v.p, v.ng, v.ng).pdfDirW;
  return pmf * light.pdfLe(v.p, v.ng, Vec3(0.f, 0.f, 1.f)).pdfPosA;
}
float pdfLightOrigin(const Scene& scene, const PathVertex& v) {
  return v.light < 0 ? 0.f : pdfLightOrigin(scene, v, scene.lights().pmf(v.light));
}

// Area density at `next` of being sampled at `v`, having arrived at `v` from `prev`.
float pdfArea(const Scene& scene, const Camera& camera, const PathVertex& v, const PathVertex* prev,
              const PathVertex& next, TransportMode mode) {
  switch (v.type) {
    case VertexType::Camera: {
      // An orthographic camera samples the film position, a planar density (v.isInfinite).
      if (camera.isOrthographic()) return convertDensity(camera.pdfWe(Ray{v.p, camera.forward()}).pdfPosA, v, next);
      const CameraPdf c = camera.pdfWe(Ray{v.p, glm::normalize(next.p - v.p)});
      return convertDensity(c.pdfDirW, v, next);
    }
    case VertexType::Light:
      return pdfLightToward(scene, v, next);
    case VertexType::Surface: {
      if (!prev) return 0.f;
      const Bsdf bsdf(v.ns, v.ng, evalMaterial(scene.material(v.material), ShadingInputs{v.uv, v.uv1, v.color}, scene.textures()));
      // Toward a light at infinity the direction is -ng exactly; its p is only a far point.
      auto toward = [&](const PathVertex& w) { return w.isInfinite ? -w.ng : glm::normalize(w.p - v.p); };
      const float pdfW = bsdf.pdf(toward(*prev), toward(next), mode);
      return convertDensity(pdfW, v, next);
    }
    case VertexType::Medium: {
      if (!prev) return 0.f;
      auto toward = [&](const PathVertex& w) { return w.isInfinite ? -w.ng : glm::normalize(w.p - v.p); };
      return convertDensity(phaseHG(toward(*prev), toward(next), scene.medium(v.media.inside).g), v, next);
    }
  }
  return 0.f;
}

}  // namespace

float pdfNeeOrigin(const Scene& scene, const PathVertex& x0, const PathVertex& x1) {
  if (x0.light < 0) return 0.f;
  return pdfLightOrigin(scene, x0, scene.lights().pmfNee(neeContext(x1), x0.light));
}

const char* misHeuristicName(MisHeuristic h) {
  switch (h) {
    case MisHeuristic::Balance: return "balance";
    case MisHeuristic::Power: return "power";
    case MisHeuristic::Uniform: return "uniform";
    case MisHeuristic::Off: return "off";
    case MisHeuristic::VarianceAware: return "variance-aware";
    case MisHeuristic::Optimal: return "optimal";
  }
  return "?";
}

std::optional<MisHeuristic> misHeuristicFromName(std::string_view name) {
  for (int h = 0; h < kMisHeuristicCount; ++h)
    if (name == misHeuristicName(static_cast<MisHeuristic>(h))) return static_cast<MisHeuristic>(h);
  return std::nullopt;
}

PathDensities pathDensities(const Scene& scene, const Camera& camera, const MisPath& path) {
  PathDensities d;
  pathDensities(scene, camera, path, d);
  return d;
}

ConnectionEnds connectionEnds(const MisPath& path) {
  const int s = path.s, t = path.t;
  ConnectionEnds e;
  e.pt = &cameraVertex(path, t - 1);
  if (t >= 2) e.ptMinus = &cameraVertex(path, t - 2);
  if (s >= 1) e.qs = &lightVertex(path, s - 1);
  if (s >= 2) e.qsMinus = &lightVertex(path, s - 2);
  return e;
}

ConnectionDensities connectionDensities(const Scene& scene, const Camera& camera, const MisPath& path,
                                        const ConnectionEnds& e) {
  const PathVertex& pt = *e.pt;
  // Density at `next` of scattering at v (from prev): the connection's own evaluation when it
  // made one at v (`known`), else a fresh one.
  const ConnectionPdfs* given = path.pdfs;
  auto scatters = [](const PathVertex& v) { return v.type == VertexType::Surface || v.type == VertexType::Medium; };
  const bool atLight = given && given->atLight && e.qs && scatters(*e.qs);
  const bool atCamera = given && given->atCamera && scatters(pt);
  auto scatter = [&](const PathVertex& v, const PathVertex* prev, const PathVertex& next, TransportMode mode,
                     bool known, float knownPdfW) {
    return known ? convertDensity(knownPdfW, v, next) : pdfArea(scene, camera, v, prev, next, mode);
  };
  // Only the densities some technique's ratio uses: pt's from the light side when a technique with
  // fewer camera vertices exists (t >= 2), its predecessor's when one with t - 2 >= 1 does.
  const int t = path.t;
  // Both ends are surface or medium vertices the connection evaluated (s, t >= 2).
  if (atLight && atCamera) return evaluatedConnectionDensities(*e.qs, pt, *given, e.qsMinus != nullptr, t);
  ConnectionDensities c;
  if (t >= 2)
    c.ptFromLight = e.qs ? scatter(*e.qs, e.qsMinus, pt, TransportMode::Importance, atLight, atLight ? given->qsToPt : 0.f)
                         : pdfLightOrigin(scene, pt);
  if (t >= 3)
    c.ptMinusFromLight =
        e.qs ? scatter(pt, e.qs, *e.ptMinus, TransportMode::Importance, atCamera, atCamera ? given->ptToPrev : 0.f)
             : pdfLightToward(scene, pt, *e.ptMinus);
  if (e.qs) {
    const bool atLens = given && given->atLens && pt.type == VertexType::Camera;
    c.qsFromCamera = atLens ? convertDensity(given->lensToQs, pt, *e.qs)
                            : scatter(pt, e.ptMinus, *e.qs, TransportMode::Radiance, atCamera, atCamera ? given->ptToQs : 0.f);
  }
  if (e.qsMinus)
    c.qsMinusFromCamera =
        scatter(*e.qs, &pt, *e.qsMinus, TransportMode::Radiance, atLight, atLight ? given->qsToPrev : 0.f);
  return c;
}

void pathDensities(const Scene& scene, const Camera& camera, const MisPath& path, PathDensities& d) {
  const int s = path.s, t = path.t, n = s + t;
  d.n = n;
  d.factors = nullptr;
  // resize, not assign: the loops below write every entry exactly once.
  d.pFromLight.resize(static_cast<size_t>(n));
  d.pFromCamera.resize(static_cast<size_t>(n));
  d.delta.resize(static_cast<size_t>(n));
  d.edgeLength2.resize(static_cast<size_t>(std::max(n - 1, 0)));
  auto vertex = [&](int i) -> const PathVertex& {
    return i < s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i);
  };

  for (int i = 0; i < s; ++i) {
    const PathVertex& v = lightVertex(path, i);
    d.pFromLight[static_cast<size_t>(i)] = v.pdfFwdA;
    d.pFromCamera[static_cast<size_t>(i)] = v.pdfRevA;
    d.delta[static_cast<size_t>(i)] = v.isDelta;
  }
  for (int j = 0; j < t; ++j) {
    const PathVertex& v = cameraVertex(path, j);
    d.pFromCamera[static_cast<size_t>(n - 1 - j)] = v.pdfFwdA;
    d.pFromLight[static_cast<size_t>(n - 1 - j)] = v.pdfRevA;
    d.delta[static_cast<size_t>(n - 1 - j)] = v.isDelta;
  }

  // The patches: qs = x(s-1), pt = x(s) are now connected.
  const ConnectionEnds ends = connectionEnds(path);
  const ConnectionDensities c = connectionDensities(scene, camera, path, ends);
  // pFromLight of the camera vertex (t = 1) and of the last before it (t = 2) would belong to a
  // technique with t' = 0, which does not exist: they are never read.
  d.pFromLight[static_cast<size_t>(s)] = c.ptFromLight;
  if (ends.ptMinus) d.pFromLight[static_cast<size_t>(s + 1)] = c.ptMinusFromLight;
  if (ends.qs) d.pFromCamera[static_cast<size_t>(s - 1)] = c.qsFromCamera;
  if (ends.qsMinus) d.pFromCamera[static_cast<size_t>(s - 2)] = c.qsMinusFromCamera;
  d.delta[static_cast<size_t>(s)] = false;
  if (s >= 1) d.delta[static_cast<size_t>(s - 1)] = false;

  for (int i = 0; i + 1 < n; ++i) d.edgeLength2[static_cast<size_t>(i)] = edgeLength2(vertex(i), vertex(i + 1));
  d.x0CanBeHit = canBeHitAsOrigin(vertex(0));
  d.x0Infinite = vertex(0).isInfinite;
  // The light choice evaluated afresh (not the walks' stored pdfNeeA: the fast weights' test
  // oracle checks those), the position or direction density x0 has either way kept.
  d.x0Nee = d.pFromLight[0];
  d.neeRefused = false;
  if (n >= 3 && scene.lights().neeByContext()) {
    const PathVertex& x0 = vertex(0);
    const LightSet& lights = scene.lights();
    const double pmfOrigin = x0.light >= 0 ? lights.pmf(x0.light) : 0.0;
    d.x0Nee = pmfOrigin > 0.0 ? d.pFromLight[0] * (lights.pmfNee(neeContext(vertex(1)), x0.light) / pmfOrigin)
                              : pdfNeeOrigin(scene, x0, vertex(1));
    d.neeRefused = d.x0Nee == 0.0;
  }
  d.equiangular = 0.0;
  if (n >= 3) {
    const double f = equiangularFactor(scene, vertex(0), vertex(1), vertex(2));
    if (f > 0.0) d.equiangular = f * remap0(d.pFromCamera[1]) / remap0(d.pFromLight[1]);
  }
}

uint64_t sampleableTechniques(const MisPath& path) {
  const int s = path.s, t = path.t, n = s + t;
  if (n > kSampleableBits) return 0;
  auto vertex = [&](int i) -> const PathVertex& {
    return i < s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i);
  };
  // The connection's own ends x(s-1), x(s) were joined, so they are not delta here (as in
  // pathDensities' patches).
  auto delta = [&](int i) { return i != s && i != s - 1 && vertex(i).isDelta; };
  uint64_t bits = 0;
  bool previousDelta = delta(0);
  if (canBeHitAsOrigin(vertex(0)) && !previousDelta) bits |= 1;
  for (int sp = 1; sp < n; ++sp) {
    const bool d = delta(sp);
    const bool lensToInfinity = sp == 1 && n == 2 && vertex(0).isInfinite;
    if (!previousDelta && !d && !lensToInfinity) bits |= uint64_t{1} << sp;
    previousDelta = d;
  }
  return bits;
}

void techniqueDensityRatios(const Scene& scene, const Camera& camera, const MisPath& path, double* ratios) {
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  const int s = path.s, n = d.n;
  ratios[s] = 1.0;
  double r = 1.0;
  for (int sp = s + 1; sp < n; ++sp) {
    r *= ratioToLight(d, sp);
    ratios[sp] = r;
  }
  r = 1.0;
  for (int sp = s - 1; sp >= 0; --sp) {
    r *= ratioToCamera(d, sp);
    ratios[sp] = r;
  }
}

UsableTechniques::UsableTechniques(const PathDensities& d, const TechniqueSet& techniques, float minConnectionDistance,
                                   MediumSampling mediumSampling)
    : d_(d), techniques_(techniques), medium_(mediumSampling) {
  const float min2 = minConnectionDistance * minConnectionDistance;
  if (!(min2 > 0.f)) return;
  bool anyShort = false;
  for (const float l2 : d.edgeLength2) anyShort |= l2 < min2;
  if (!anyShort) return;
  // Exclude short connections only when a technique without one can still produce the path:
  // otherwise the path would have no technique at all and the estimate would lose it.
  minDistance2_ = min2;
  for (int sp = 0; sp < d.n; ++sp)
    if (enabledAndPossible(sp) && !shortConnection(sp)) return;
  if (equiangularPossible() && !shortConnection(1)) return;
  minDistance2_ = 0.f;
}

bool UsableTechniques::enabledAndPossible(int sp) const {
  if (sp == 1 && medium_ == MediumSampling::Equiangular && equiangularPossible()) return false;  // E in its place
  return techniques_.contains(sp, d_.n - sp) && techniquePossible(d_, sp);
}

// Technique s' >= 1 joins x(s'-1) and x(s'), edge s' - 1; s' = 0 connects nothing.
bool UsableTechniques::shortConnection(int sp) const {
  return sp >= 1 && d_.edgeLength2[static_cast<size_t>(sp - 1)] < minDistance2_;
}

bool UsableTechniques::operator()(int sp) const { return enabledAndPossible(sp) && !shortConnection(sp); }

// E joins x0 and x1 as C(1, n-1) does.
bool UsableTechniques::equiangular() const { return equiangularPossible() && !shortConnection(1); }

bool UsableTechniques::equiangularPossible() const {
  return medium_ != MediumSampling::Distance && d_.equiangular > 0.0 &&
         techniques_.contains(Technique::equiangular(d_.n - 1));
}

int techniquesEnabledOfLength(const TechniqueSet& techniques, int k, MediumSampling mediumSampling) {
  int count = 0;
  for (int s = 0; s <= k; ++s) count += techniques.contains(s, k + 1 - s) ? 1 : 0;
  if (mediumSampling != MediumSampling::Distance && k >= 2 && techniques.contains(Technique::equiangular(k))) ++count;
  return count;
}

float minConnectionDistance(const Scene& scene, const MisOptions& options) {
  return options.minConnection * scene.bounds().radius;
}

// Weight of technique s (or of E(1, n-1), ofEquiangular) among the usable ones for the path whose
// densities are d (mis.h).
double weightFromDensities(const PathDensities& d, int s, const TechniqueSet& techniques, const MisOptions& options,
                           float lightTracingRatio, float minDistance, bool ofEquiangular) {
  const int n = d.n;
  if (options.heuristic == MisHeuristic::Off) {
    // Veach 1997 sec. 9.1 (naive combination): 1 / n_k for every enabled technique of length
    // k = n - 1, whether or not the others can produce this path; no short-connection exclusion
    // (the weight does not look at the path). Zero where (s, t) itself cannot form the path.
    if (ofEquiangular ? !(options.mediumSampling != MediumSampling::Distance && d.equiangular > 0.0 &&
                          techniques.contains(Technique::equiangular(n - 1)))
                      : !techniques.contains(s, n - s) || !techniquePossible(d, s))
      return 0.0;
    return 1.0 / static_cast<double>(techniquesEnabledOfLength(techniques, n - 1, options.mediumSampling));
  }
  const UsableTechniques usable(d, techniques, minDistance, options.mediumSampling);
  if (ofEquiangular ? !usable.equiangular() : !usable(s)) return 0.0;
  const bool equiangular = usable.equiangular();

  if (options.heuristic == MisHeuristic::Uniform) {
    // 1 / (number of enabled techniques able to produce this path), counted.
    int count = equiangular ? 1 : 0;
    for (int sp = 0; sp < n; ++sp) count += usable(sp) ? 1 : 0;
    return 1.0 / static_cast<double>(count);
  }

  // Veach 1997 eq. 10.9 (balance: beta = 1) and the power heuristic with exponent beta:
  //   w_s = (n_s p_s)^beta / sum_i (n_i p_i)^beta,
  // with p_i the density of the path under technique i (s' = i light vertices) and n_i its sample
  // count (lightTracingRatio for t' = 1, else 1). The ratios come from Veach eq. 10.10:
  //   p_{i+1} / p_i = pFromLight(x_i) / pFromCamera(x_i),
  // walked outward from i = s so that no p_i is formed on its own (ratioToLight, ratioToCamera:
  // with x0's next-event density for i + 1 = 1). E(1, n-1), one sample per camera sample, has
  // p_E = p_2 d.equiangular; its own weight walks from s = 2.
  // Variance-aware: the balance heuristic with each n_i times its factor c_i (variance_aware_mis.h;
  // E's at its own slot, 2(n - 1)).
  const double beta = options.heuristic == MisHeuristic::Power ? static_cast<double>(options.beta) : 1.0;
  auto count = [&](int sp) { return ((n - sp == 1) ? static_cast<double>(lightTracingRatio) : 1.0) * d.factor(sp); };
  const int from = ofEquiangular ? 2 : s;
  // Read only where E is weighed (n >= 3 then): factors of a length without E may stop at slot 2k - 1.
  const double equiangularCount = ofEquiangular || equiangular ? d.factor(Technique::equiangular(n - 1).slot()) : 1.0;
  const double own = ofEquiangular ? d.equiangular * equiangularCount : count(s);
  auto term = [beta](double x) { return beta == 1.0 ? x : beta == 2.0 ? x * x : std::pow(x, beta); };
  double sum = ofEquiangular ? (usable(2) ? term(count(2) / own) : 0.0) : 1.0;  // the walk's start
  double r = 1.0, r2 = 1.0;  // r2 = p_2 / p_from
  for (int sp = from + 1; sp < n; ++sp) {  // more light vertices: x(sp-1) moves to the light side
    r *= ratioToLight(d, sp);
    if (sp == 2) r2 = r;
    if (usable(sp)) sum += term(r * count(sp) / own);
  }
  r = 1.0;
  for (int sp = from - 1; sp >= 0; --sp) {  // fewer light vertices: x(sp) moves to the camera side
    r *= ratioToCamera(d, sp);
    if (sp == 2) r2 = r;
    if (usable(sp)) sum += term(r * count(sp) / own);
  }
  if (equiangular) sum += term(r2 * d.equiangular * equiangularCount / own);  // one for E itself
  return 1.0 / sum;
}

float misWeight(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                const MisOptions& options, float lightTracingRatio, const float* factors) {
  if (!techniques.contains(path.s, path.t)) return 0.f;
  // No light subpath connects to an orthographic camera (a delta in direction): t = 1 samples nothing.
  if (path.t == 1 && camera.isOrthographic()) return 0.f;
  // Per-thread scratch: misWeight runs for every technique of every sample, so it must not
  // allocate; the result still depends only on the arguments.
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  d.factors = factors;
  const double w =
      weightFromDensities(d, path.s, techniques, options, lightTracingRatio, minConnectionDistance(scene, options));
  return std::isfinite(w) ? static_cast<float>(w) : 0.f;
}

double misWeightSum(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                    const MisOptions& options, float lightTracingRatio, const float* factors) {
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  d.factors = factors;
  const float minDistance = minConnectionDistance(scene, options);
  double sum = 0.0;
  for (int sp = 0; sp < d.n; ++sp)
    sum += weightFromDensities(d, sp, techniques, options, lightTracingRatio, minDistance);
  return sum + weightFromDensities(d, 1, techniques, options, lightTracingRatio, minDistance, true);
}

float equiangularMisWeight(const Scene& scene, const Camera& camera, const MisPath& path,
                           const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio,
                           const float* factors) {
  if (options.mediumSampling == MediumSampling::Distance || path.s != 1 || path.t < 2) return 0.f;
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  d.factors = factors;
  const double w = weightFromDensities(d, 1, techniques, options, lightTracingRatio,
                                       minConnectionDistance(scene, options), true);
  return std::isfinite(w) ? static_cast<float>(w) : 0.f;
}

double lightWalkWeight(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                       const MisOptions& options, float lightTracingRatio, const float* factors, bool ofEquiangular) {
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  d.factors = factors;
  const int n = d.n;
  const UsableTechniques usable(d, techniques, minConnectionDistance(scene, options), options.mediumSampling);
  // The balance weights' terms n_i p_i relative to the sampling technique's density, walked outward
  // from a reference technique as weightFromDensities walks them (one walk, O(n)): the sum over the
  // usable techniques, and over those that walk a light subpath (never E(1, n-1) nor s' <= 1 with
  // t' >= 2). The reference is s = 2 for E's own sample (its density is p_2 d.equiangular).
  const int from = ofEquiangular ? 2 : path.s;
  auto count = [&](int sp) { return ((n - sp == 1) ? static_cast<double>(lightTracingRatio) : 1.0) * d.factor(sp); };
  auto walks = [&](int sp) { return usesLightSubpath(sp, n - sp) && !(sp == n - 1 && camera.isOrthographic()); };
  double total = 0.0, light = 0.0, r = 1.0, r2 = 1.0;
  auto addTerm = [&](int sp, double ratio) {
    if (!usable(sp)) return;
    const double term = ratio * count(sp);
    total += term;
    if (walks(sp)) light += term;
  };
  addTerm(from, 1.0);
  for (int sp = from + 1; sp < n; ++sp) {
    r *= ratioToLight(d, sp);
    if (sp == 2) r2 = r;
    addTerm(sp, r);
  }
  r = 1.0;
  for (int sp = from - 1; sp >= 0; --sp) {
    r *= ratioToCamera(d, sp);
    if (sp == 2) r2 = r;
    addTerm(sp, r);
  }
  if (usable.equiangular())
    total += r2 * d.equiangular * d.factor(Technique::equiangular(n - 1).slot());  // E: camera side
  const double w = total > 0.0 ? light / total : 0.0;
  return std::isfinite(w) ? w : 0.0;
}

int balanceWeights(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                   const MisOptions& options, float lightTracingRatio, const float* factors, double* weights) {
  thread_local PathDensities d;
  pathDensities(scene, camera, path, d);
  d.factors = factors;
  const int n = d.n;
  const UsableTechniques usable(d, techniques, minConnectionDistance(scene, options), options.mediumSampling);
  // n_i p_i / (n_s p_s) walked outward from the sampling technique s as weightFromDensities walks
  // them (Veach 1997 eq. 10.10), then normalised: w_i = n_i p_i / sum_j n_j p_j.
  auto count = [&](int sp) { return ((n - sp == 1) ? static_cast<double>(lightTracingRatio) : 1.0) * d.factor(sp); };
  const int from = path.s;
  for (int sp = 0; sp < n; ++sp) weights[sp] = 0.0;
  double total = 0.0, r = 1.0;
  auto put = [&](int sp, double ratio) {
    if (!usable(sp)) return;
    weights[sp] = ratio * count(sp);
    total += weights[sp];
  };
  put(from, 1.0);
  for (int sp = from + 1; sp < n; ++sp) put(sp, r *= ratioToLight(d, sp));
  r = 1.0;
  for (int sp = from - 1; sp >= 0; --sp) put(sp, r *= ratioToCamera(d, sp));
  if (!(total > 0.0) || !std::isfinite(total)) {
    for (int sp = 0; sp < n; ++sp) weights[sp] = 0.0;
    return n;
  }
  for (int sp = 0; sp < n; ++sp) weights[sp] /= total;
  return n;
}

}  // namespace pathlab
