// techniquesOnPath: the path's densities once, then every technique's product and weights.
#include "core/bpt/path_techniques.h"

namespace pathlab {

namespace {

// Every technique of the path whose densities are d (`surface[i]`: x_i lies on a surface;
// `sampleable`: bit s' when connection s' can sample it at all).
std::vector<TechniqueOnPath> techniquesOnDensities(const PathDensities& d, const std::vector<uint8_t>& surface,
                                                   uint64_t sampleable, const TechniqueSet& techniques,
                                                   const MisOptions& options, float minDistance, float lightTracingRatio,
                                                   const std::optional<MergesOnPath>& merges, const float* factors,
                                                   const float* counts = nullptr) {
  MisOptions balance = options, power = options, uniform = options, varianceAware = options;
  balance.heuristic = MisHeuristic::Balance;
  power.heuristic = MisHeuristic::Power;
  uniform.heuristic = MisHeuristic::Uniform;
  varianceAware.heuristic = MisHeuristic::VarianceAware;
  // The same densities with the factors, for the variance-aware weight. Sample counts other than
  // one (--light-paths) multiply every heuristic's n_i alike, through the same slot.
  PathDensities withCounts = d;
  withCounts.factors = counts;
  PathDensities withFactors = d;
  withFactors.factors = factors ? factors : counts;
  const UsableTechniques usable(d, techniques, minDistance, options.mediumSampling);
  // p_C(s'): the light-side densities before s', the camera-side ones from s' on.
  auto connectionDensity = [&](int sp) {
    double p = 1.0;
    for (int i = 0; i < d.n; ++i) p *= remap0(i < sp ? lightSideDensity(d, i, sp) : d.pFromCamera[static_cast<size_t>(i)]);
    return p;
  };
  auto weigh = [&](TechniqueOnPath& x) {
    if (merges) {
      const Technique y = x.technique();
      x.balance = weightWithMerges(d, surface, y, techniques, balance, lightTracingRatio, minDistance, merges->mis);
      x.power = weightWithMerges(d, surface, y, techniques, power, lightTracingRatio, minDistance, merges->mis);
      x.uniform = weightWithMerges(d, surface, y, techniques, uniform, lightTracingRatio, minDistance, merges->mis);
      x.varianceAware =
          weightWithMerges(withFactors, surface, y, techniques, varianceAware, lightTracingRatio, minDistance, merges->mis);
    } else {
      x.balance = weightFromDensities(withCounts, x.s, techniques, balance, lightTracingRatio, minDistance);
      x.power = weightFromDensities(withCounts, x.s, techniques, power, lightTracingRatio, minDistance);
      x.uniform = weightFromDensities(withCounts, x.s, techniques, uniform, lightTracingRatio, minDistance);
      x.varianceAware = weightFromDensities(withFactors, x.s, techniques, varianceAware, lightTracingRatio, minDistance);
    }
    x.factor = factors ? withFactors.factor(x.technique().slot()) : 1.0;
  };
  std::vector<TechniqueOnPath> out;
  for (int sp = 0; sp < d.n; ++sp) {
    TechniqueOnPath x;
    x.s = sp;
    x.t = d.n - sp;
    x.possible = (sampleable >> sp) & 1u;
    x.enabled = techniques.contains(x.s, x.t);
    x.connectionEdge = sp >= 1 ? sp - 1 : -1;
    x.counted = usable(sp);
    if (x.possible) {
      x.pdfA = connectionDensity(sp);
      weigh(x);
    }
    out.push_back(x);
  }
  // E(1, n-1) where it is on and can sample the path: p_E = p_C(2) d.equiangular.
  if (!merges && options.mediumSampling != MediumSampling::Distance && d.equiangular > 0.0) {
    TechniqueOnPath x;
    x.s = 1;
    x.t = d.n - 1;
    x.kind = TechniqueKind::Equiangular;
    x.possible = true;
    x.enabled = techniques.contains(x.technique());
    x.connectionEdge = 0;
    x.counted = usable.equiangular();
    x.pdfA = connectionDensity(2) * d.equiangular;
    x.balance = weightFromDensities(withCounts, 1, techniques, balance, lightTracingRatio, minDistance, true);
    x.power = weightFromDensities(withCounts, 1, techniques, power, lightTracingRatio, minDistance, true);
    x.uniform = weightFromDensities(withCounts, 1, techniques, uniform, lightTracingRatio, minDistance, true);
    x.varianceAware = weightFromDensities(withFactors, 1, techniques, varianceAware, lightTracingRatio, minDistance, true);
    x.factor = factors ? withFactors.factor(x.technique().slot()) : 1.0;
    out.push_back(x);
  }
  if (!merges) return out;
  // M(s', n + 1 - s'), s' = 2 .. n - 1: the connection C(s')'s density times the acceptance
  // probability pi r^2 pFromCamera(x_{s'-1}) (Georgiev et al. 2012 eq. 10; a zero camera-side
  // density there, a delta lobe beside it, counts one as in the weights) and the probability that
  // the pass kept x_{s'-1} (mergeKeep).
  const double area = 3.14159265358979323846 * static_cast<double>(merges->radius) * static_cast<double>(merges->radius);
  const int onlySite = onlyMergeSite(d, merges->mis);
  for (int sp = 2; sp <= d.n - 1; ++sp) {
    TechniqueOnPath x;
    x.s = sp;
    x.t = d.n + 1 - sp;
    x.kind = TechniqueKind::Merge;
    x.mergedVertex = sp - 1;
    // Under ppm only the merge at the camera's first non-delta vertex (as weightWithMerges counts).
    x.possible = mergeableVertex(d, surface, sp - 1) && (onlySite == 0 || sp == onlySite);
    x.enabled = techniques.contains(x.technique());
    x.counted = x.possible && x.enabled;
    if (x.possible) {
      x.pdfA = connectionDensity(sp) * area * remap0(d.pFromCamera[static_cast<size_t>(sp - 1)]) *
               mergeKeep(merges->mis.nonCaustic, d.delta[static_cast<size_t>(sp - 2)]);
      weigh(x);
    }
    out.push_back(x);
  }
  return out;
}

// Which vertices of `path` lie on surfaces: a merge needs one (mergeableVertex).
std::vector<uint8_t> surfaceVertices(const MisPath& path, int n) {
  std::vector<uint8_t> surface(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const PathVertex& v = i < path.s ? lightVertex(path, i) : cameraVertex(path, n - 1 - i);
    surface[static_cast<size_t>(i)] = v.type == VertexType::Surface;
  }
  return surface;
}

}  // namespace

std::vector<TechniqueOnPath> techniquesOnPath(const Scene& scene, const Camera& camera, const MisPath& path,
                                              const TechniqueSet& techniques, const MisOptions& options,
                                              float lightTracingRatio, const std::optional<MergesOnPath>& merges,
                                              const float* factors, const float* counts) {
  const PathDensities d = pathDensities(scene, camera, path);
  const uint64_t sampleable = d.n <= kSampleableBits ? sampleableTechniques(path) : 0;
  return techniquesOnDensities(d, surfaceVertices(path, d.n), sampleable, techniques, options,
                               minConnectionDistance(scene, options), lightTracingRatio, merges, factors, counts);
}

std::vector<TechniqueOnPath> techniquesOnMergedPath(const Scene& scene, const MisPath& path, const MergedPath& merged,
                                                    const TechniqueSet& techniques, const MisOptions& options,
                                                    float lightTracingRatio, const MergesOnPath& merges,
                                                    const float* factors) {
  // Which techniques can sample it at all is a property of its vertices' kinds (delta lobes,
  // surfaces), the same on the merged path as on the connection C(s, t - 1) through y(s-1).
  const uint64_t sampleable = path.s + path.t <= kSampleableBits ? sampleableTechniques(path) : 0;
  return techniquesOnDensities(merged.densities, merged.surface, sampleable, techniques, options,
                               minConnectionDistance(scene, options), lightTracingRatio, merges, factors);
}

void tracePath(const Scene& scene, const Camera& camera, const MisPath& path, TracedPath& out,
               const PathDensities* densities) {
  const PathDensities d = densities ? *densities : pathDensities(scene, camera, path);
  out = TracedPath{};
  for (int i = 0; i < d.n; ++i) {
    // x_i: the light prefix first, then the camera prefix from its far end back to the lens.
    const PathVertex& v = i < path.s ? lightVertex(path, i) : cameraVertex(path, d.n - 1 - i);
    out.p.push_back(v.p);
    out.kind.push_back(v.type == VertexType::Camera  ? TracedVertexKind::Camera
                       : v.type == VertexType::Light ? TracedVertexKind::Light
                       : v.type == VertexType::Medium ? TracedVertexKind::Medium
                                                      : TracedVertexKind::Surface);
    out.delta.push_back(d.delta[static_cast<size_t>(i)]);
    out.deltaPosition.push_back(v.isDeltaPosition ? 1 : 0);
    out.pFromLight.push_back(d.pFromLight[static_cast<size_t>(i)]);
    out.pFromCamera.push_back(d.pFromCamera[static_cast<size_t>(i)]);
  }
  out.x0Nee = d.x0Nee;
}

}  // namespace pathlab
