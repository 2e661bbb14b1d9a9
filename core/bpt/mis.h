// The multiple importance sampling weight of bidirectional technique (s, t) for one path, as a
// pure function of the two subpath prefixes (Veach 1997, sec. 10.3; pbrt-v4 MISWeight without
// ScopedAssignment; Tungsten LightPath::misWeight).
#pragma once

#include "core/bpt/connect.h"
#include "core/bpt/mis_options.h"
#include "core/bpt/path_vertex.h"
#include "core/bpt/technique_set.h"
#include "core/camera/camera.h"
#include "core/scene/scene.h"

#include <cstdint>
#include <vector>

namespace pathlab {

struct MisPath {
  const PathVertex* lightPath = nullptr;  // at least s vertices
  int s = 0;
  const PathVertex* cameraPath = nullptr;  // at least t vertices
  int t = 1;
  // The fresh endpoint of Connection::sampled: t = 1 replaces cameraPath[0] (the lens point);
  // s = 1 with t >= 2 replaces lightPath[0] (the light sample). nullptr when none was drawn.
  const PathVertex* sampled = nullptr;
  // The connection's own BSDF densities at its endpoints (Connection::pdfs); nullptr: recompute
  // them from the vertices (the tests' reference path).
  const ConnectionPdfs* pdfs = nullptr;
};

// Vertex i of the light prefix and j of the camera prefix as the weights see them: with the fresh
// endpoint of the connection in place of x0 (s = 1, t >= 2) or of the lens vertex (t = 1).
inline const PathVertex& lightVertex(const MisPath& path, int i) {
  return (i == 0 && path.s == 1 && path.t >= 2 && path.sampled) ? *path.sampled : path.lightPath[i];
}
inline const PathVertex& cameraVertex(const MisPath& path, int j) {
  return (j == 0 && path.t == 1 && path.sampled) ? *path.sampled : path.cameraPath[j];
}

// The four vertices around the connection of technique (s, t) with the fresh endpoint substituted:
// qs = x(s-1) and its predecessor on the light side, pt = x(s) and its predecessor on the camera
// side (null where the subpath is too short).
struct ConnectionEnds {
  const PathVertex* qsMinus = nullptr;
  const PathVertex* qs = nullptr;
  const PathVertex* pt = nullptr;
  const PathVertex* ptMinus = nullptr;
};
ConnectionEnds connectionEnds(const MisPath& path);

// x0's density when next-event estimation chooses its light for x1 (LightSet::pmfNee) and samples
// it as a light subpath's origin would (the position, or at infinity the direction, density).
float pdfNeeOrigin(const Scene& scene, const PathVertex& x0, const PathVertex& x1);

// The densities a connection changes (pbrt-v4 MISWeight's four ScopedAssignments; Veach 1997 sec.
// 10.3.4), in area measure: the path's other vertices keep the densities their walks gave them.
struct ConnectionDensities {
  float ptFromLight = 0.f;        // pt sampled from qs, or as a light's origin (s = 0) (t >= 2)
  float ptMinusFromLight = 0.f;   // pt's predecessor sampled from pt having arrived from qs (t >= 3)
  float qsFromCamera = 0.f;       // qs sampled from pt (s >= 1)
  float qsMinusFromCamera = 0.f;  // qs's predecessor sampled from qs having arrived from pt (s >= 2)
};
// connectionDensities where the connection evaluated the scattering at both of its ends (s, t >= 2,
// surface or medium vertices; formInteriorConnection): the two conversions across the connection
// edge share its geometry, and each end's conversion toward its own predecessor was stored by its
// walk (PathVertex::areaToPrev). convertDensity's arithmetic, regrouped. Inline for the partial
// sums' interior weight (misWeightInterior), which must give connectionDensities' bits.
[[gnu::always_inline]] inline ConnectionDensities evaluatedConnectionDensities(const PathVertex& qs, const PathVertex& pt,
                                                                              const ConnectionPdfs& given, bool hasQsMinus,
                                                                              int t) {
  ConnectionDensities c;
  const Vec3 d = qs.p - pt.p;
  const float dist2 = glm::dot(d, d);
  const float dist = std::sqrt(dist2);
  const float invDist3 = 1.f / (dist2 * dist);
  // A medium vertex receives with the volume measure: no cosine (|d| in its place).
  auto cosine = [&](const PathVertex& v) { return v.type == VertexType::Medium ? dist : absDot(v.ng, d); };
  c.qsFromCamera = given.ptToQs * (cosine(qs) * invDist3);
  c.ptFromLight = given.qsToPt * (cosine(pt) * invDist3);
  if (hasQsMinus) c.qsMinusFromCamera = given.qsToPrev * qs.areaToPrev;
  if (t >= 3) c.ptMinusFromLight = given.ptToPrev * pt.areaToPrev;
  return c;
}
// The connection's own BSDF densities (MisPath::pdfs) where it evaluated them, else fresh ones.
ConnectionDensities connectionDensities(const Scene& scene, const Camera& camera, const MisPath& path,
                                        const ConnectionEnds& ends);

// pbrt's "remap zero to one": a delta density cancels between the techniques that share it.
inline double remap0(double p) { return p != 0.0 ? p : 1.0; }

// Weight of technique (s, t) among the enabled techniques able to produce the same path.
// `lightTracingRatio` = light subpaths per pass / camera samples per pass (the sample counts n_i
// of Veach's multi-sample model for t = 1 against t >= 2); see bidir_tracer.h.
// Returns 0 when (s, t) itself is disabled or impossible. MisHeuristic::Off: 1 / n_k whatever the
// other techniques can do, so misWeightSum is then the share of n_k that can produce the path.
// `factors`: variance-aware MIS's factors of the path's length at its pixel (PathDensities::factors).
float misWeight(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                const MisOptions& options, float lightTracingRatio = 1.f, const float* factors = nullptr);

// The sum over every enabled technique able to produce this path of its weight (the path's own
// densities, each technique's ratios walked from it): one whenever the weights are a partition of
// unity (Veach 1997 eq. 9.11). For the checkMis setting and the tests.
double misWeightSum(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                    const MisOptions& options, float lightTracingRatio = 1.f, const float* factors = nullptr);

// The weight of the equiangular technique E(1, t) for its own sample: `path` holds E's light
// sample (s = 1, `sampled`) and the camera prefix with E's vertex last (t vertices). Zero when
// options.mediumSampling is Distance or E cannot sample the path.
float equiangularMisWeight(const Scene& scene, const Camera& camera, const MisPath& path,
                           const TechniqueSet& techniques, const MisOptions& options, float lightTracingRatio = 1.f,
                           const float* factors = nullptr);

// The sum of the weights misWeight gives the path's techniques that walk a light subpath (light
// tracing and s >= 2: light_paths.h usesLightSubpath), whichever technique sampled it: w_L of
// --light-paths auto's variances (light_path_choice.h). `factors` as for misWeight; ofEquiangular: `path`
// is E(1, t)'s own sample (equiangularMisWeight's). One walk over the densities, O(s + t).
double lightWalkWeight(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                       const MisOptions& options, float lightTracingRatio = 1.f, const float* factors = nullptr,
                       bool ofEquiangular = false);

// The balance heuristic's weight of every technique of the path's length, whichever sampled it:
// weights[s'] = n_s' p_s' / sum_j n_j p_j for s' in 0 .. n-1 (n = s + t, returned; zero for the
// techniques misWeight does not weigh), one walk over the densities, O(n). Connections only: the
// callers (optimal MIS, core/bpt/optimal_mis.h) run without merges and the equiangular family.
// `factors` as for misWeight (--light-paths F's counts).
int balanceWeights(const Scene& scene, const Camera& camera, const MisPath& path, const TechniqueSet& techniques,
                   const MisOptions& options, float lightTracingRatio, const float* factors, double* weights);

// The densities of the whole path x0 .. x(n-1) (n = s + t, x0 on the light, x(n-1) the camera)
// after the connection: pFromLight[i] / pFromCamera[i] are the area densities of x_i sampled from
// the light / camera side, as misWeight sees them. Exposed for the tests' brute-force oracle.
struct PathDensities {
  int n = 0;
  std::vector<double> pFromLight, pFromCamera;
  std::vector<uint8_t> delta;  // delta scattering at x_i (bytes: vector<bool>'s bit access is slow)
  // |x(i+1) - x(i)|^2 of edge i, the connection edge of technique s' = i + 1; infinite toward a
  // directional light.
  std::vector<float> edgeLength2;
  bool x0CanBeHit = false;   // x0 is on an area light or the environment (technique s = 0 possible)
  bool x0Infinite = false;   // x0 is at infinity: no lens point connects to it (s' = 1, t' = 1)
  // x0's density under technique s' = 1 when n >= 3: next-event estimation chose its light for x1
  // (LightSet::pmfNee), where the techniques s' >= 2 start a light subpath there, chosen by power
  // (pFromLight[0]). Equal to pFromLight[0] for n = 2 (the light subpath's x0 meets the lens) and
  // when the scene chooses by power alone. lightSideDensity and the step ratios below use it.
  double x0Nee = 0.0;
  // A light BVH's next-event estimation cannot choose x0's light for x1 (x0Nee is zero there):
  // technique (1, t) cannot sample this path. Never set when lights are chosen by power.
  bool neeRefused = false;
  // Variance-aware MIS (variance_aware_mis.h): the factor c of each technique of the path's length
  // at its pixel, by Technique::slot(), multiplying its sample count in the balance weights; null
  // (every factor 1) under the other heuristics. Set by the weights' callers; pathDensities leaves it null.
  const float* factors = nullptr;
  double factor(int slot) const { return factors ? static_cast<double>(factors[slot]) : 1.0; }
  // The equiangular technique E(1, n-1) (equiangular_technique.h): its density over that of
  // C(2, n-2), p_E / p_2 = [x0's density with its light chosen from x2 / pFromLight(x0)]
  // pFromCamera(x1) p_e / (pFromLight(x1) p_d); 0 where E cannot sample the path. Formed against
  // p_2 rather than p_1 so that a light BVH refusing x0 for x1 (x0Nee = 0) leaves it finite.
  double equiangular = 0.0;
};
// The density of x_i as technique s' samples it from the light side (i < s'): x0 by next-event
// estimation for s' = 1, by the light subpath otherwise.
inline double lightSideDensity(const PathDensities& d, int i, int sp) {
  return i == 0 && sp == 1 ? d.x0Nee : d.pFromLight[static_cast<size_t>(i)];
}
// p_{s'} / p_{s'-1} (Veach 1997 eq. 10.10: x(s'-1) moves to the light side), and its mirror
// p_{s'} / p_{s'+1}. Going between s' = 1 and 2, x0 also changes how it is sampled (x0Nee).
inline double ratioToLight(const PathDensities& d, int sp) {
  const size_t i = static_cast<size_t>(sp - 1);
  double r = remap0(lightSideDensity(d, sp - 1, sp)) / remap0(d.pFromCamera[i]);
  if (sp == 2) r *= remap0(d.pFromLight[0]) / remap0(d.x0Nee);
  return r;
}
inline double ratioToCamera(const PathDensities& d, int sp) {
  const size_t i = static_cast<size_t>(sp);
  double r = remap0(d.pFromCamera[i]) / remap0(lightSideDensity(d, sp, sp + 1));
  if (sp == 1) r *= remap0(d.x0Nee) / remap0(d.pFromLight[0]);
  return r;
}

// Whether vertex x0 of a path can be found by a camera subpath (technique s = 0 possible): on an
// area light or the environment, not a point, spot or directional one.
inline bool canBeHitAsOrigin(const PathVertex& x0) {
  return !x0.isDeltaPosition && !x0.isDeltaDirection && x0.light >= 0 && x0.type != VertexType::Camera;
}
PathDensities pathDensities(const Scene& scene, const Camera& camera, const MisPath& path);
// The same into `d`, reusing its storage (no allocation once it has grown to the path length).
void pathDensities(const Scene& scene, const Camera& camera, const MisPath& path, PathDensities& d);

// The weight misWeight gives technique s' of the path whose densities are d (minDistance in scene
// units, minConnectionDistance), for the path inspector's "one path, every technique".
// ofEquiangular: the weight of E(1, n-1) instead (s is then ignored), over the same set.
double weightFromDensities(const PathDensities& d, int s, const TechniqueSet& techniques, const MisOptions& options,
                           float lightTracingRatio, float minDistance, bool ofEquiangular = false);

// Whether technique s' (t' = n - s') can produce a path with these delta flags. Inline: the
// weights ask it for every technique of every connection.
inline bool techniquePossible(const PathDensities& d, int sp) {
  if (sp < 0 || sp >= d.n) return false;  // t' >= 1
  if (sp == 0) return d.x0CanBeHit && !d.delta[0];
  if (sp == 1 && d.n == 2 && d.x0Infinite) return false;  // light tracing from infinity
  // Next-event estimation cannot choose x0's light for x1 (a light BVH's bounds refuse it there):
  // a zero density, not a delta. The ratios walked through s' = 1 stay right (the remapped value
  // cancels between its two steps); only its own term is left out.
  if (sp == 1 && d.neeRefused) return false;
  // The connection joins x(s'-1) and x(s'): neither may scatter by a delta lobe.
  return !d.delta[static_cast<size_t>(sp - 1)] && !d.delta[static_cast<size_t>(sp)];
}

// Bit s' (0 <= s' < n, n = s + t <= kSampleableBits) is set when technique (s', n - s') can
// produce this very path: the connection edge it would use has no delta vertex at either end, and
// s' = 0 needs x0 on an area light (techniquePossible on the same delta flags, without the
// densities). Independent of which techniques are enabled. 0 for longer paths. The technique
// maps and the consistency check (issue 13) compare each technique only on the paths it can
// sample: "cannot" is structural, not a small weight.
inline constexpr int kSampleableBits = 64;
uint64_t sampleableTechniques(const MisPath& path);

// ratios[s'] = p_{s'}(x) / p_s(x) for every s' in 0..n-1 of this path (n = s + t; ratios must
// hold n values): the densities with which each technique of the path's length would sample it,
// relative to the technique (s, t) that did (Veach 1997 eq. 10.10, walked outward from s as in
// misWeight; delta densities cancel as there). Meaningful where the technique can sample the path
// (sampleableTechniques); the consistency check uses them to estimate, from one technique's
// samples, the second moment of another's estimator (E_j[(f/p_j)^2 p_j/p_i] = E_i[(f/p_i)^2]).
void techniqueDensityRatios(const Scene& scene, const Camera& camera, const MisPath& path, double* ratios);

// The techniques misWeight weighs for a path: those enabled and possible, less those whose
// connection edge is shorter than minConnectionDistance when an enabled possible technique with a
// longer (or no) connection edge remains (MisOptions::minConnection). The set depends on the
// path alone, so the weights over it still sum to one and the estimate stays unbiased.
// With the equiangular family (mediumSampling not Distance) E(1, n-1) is one of them where it can
// sample the path and E(1, n-1) is enabled, its connection edge that of C(1, n-1); under
// MediumSampling::Equiangular C(1, n-1) is not, on the paths an enabled E(1, n-1) can sample.
class UsableTechniques {
 public:
  UsableTechniques(const PathDensities& d, const TechniqueSet& techniques, float minConnectionDistance,
                   MediumSampling mediumSampling = MediumSampling::Distance);
  bool operator()(int sPrime) const;
  bool equiangular() const;  // E(1, n-1)

 private:
  const PathDensities& d_;
  const TechniqueSet& techniques_;
  MediumSampling medium_;
  float minDistance2_ = 0.f;  // 0 when nothing is excluded for this path
  bool equiangularPossible() const;
  bool enabledAndPossible(int sPrime) const;
  bool shortConnection(int sPrime) const;
};

// n_k: the enabled techniques of length k, which MisHeuristic::Off weighs 1 / n_k each; with the
// equiangular family, E(1, k) counts at every k >= 2 where it is enabled.
int techniquesEnabledOfLength(const TechniqueSet& techniques, int k, MediumSampling mediumSampling = MediumSampling::Distance);

// MisOptions::minConnection in scene units.
float minConnectionDistance(const Scene& scene, const MisOptions& options);

}  // namespace pathlab
