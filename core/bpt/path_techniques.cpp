// techniquesOnPath: the path's densities once, then every technique's product and weights.
#include "core/bpt/path_techniques.h"

namespace pathlab {

std::vector<TechniqueOnPath> techniquesOnPath(const Scene& scene, const Camera& camera, const MisPath& path,
                                              const TechniqueSet& techniques, const MisOptions& options,
                                              float lightTracingRatio) {
  const PathDensities d = pathDensities(scene, camera, path);
  const uint64_t sampleable = d.n <= kSampleableBits ? sampleableTechniques(path) : 0;
  const float minDistance = minConnectionDistance(scene, options);
  MisOptions balance = options, power = options, uniform = options;
  balance.heuristic = MisHeuristic::Balance;
  power.heuristic = MisHeuristic::Power;
  uniform.heuristic = MisHeuristic::Uniform;
  const UsableTechniques usable(d, techniques, minDistance);
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
      double p = 1.0;
      for (int i = 0; i < d.n; ++i)
        p *= remap0(i < sp ? lightSideDensity(d, i, sp) : d.pFromCamera[static_cast<size_t>(i)]);
      x.pdfA = p;
      x.balance = weightFromDensities(d, sp, techniques, balance, lightTracingRatio, minDistance);
      x.power = weightFromDensities(d, sp, techniques, power, lightTracingRatio, minDistance);
      x.uniform = weightFromDensities(d, sp, techniques, uniform, lightTracingRatio, minDistance);
    }
    out.push_back(x);
  }
  return out;
}

void tracePath(const Scene& scene, const Camera& camera, const MisPath& path, TracedPath& out) {
  const PathDensities d = pathDensities(scene, camera, path);
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
