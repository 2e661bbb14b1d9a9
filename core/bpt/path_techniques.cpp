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
  std::vector<TechniqueOnPath> out;
  for (int sp = 0; sp < d.n; ++sp) {
    TechniqueOnPath x;
    x.s = sp;
    x.t = d.n - sp;
    x.possible = (sampleable >> sp) & 1u;
    x.enabled = techniques.contains(x.s, x.t);
    x.connectionEdge = sp >= 1 ? sp - 1 : -1;
    if (x.possible) {
      double p = 1.0;
      for (int i = 0; i < d.n; ++i)
        p *= remap0(i < sp ? d.pFromLight[static_cast<size_t>(i)] : d.pFromCamera[static_cast<size_t>(i)]);
      x.pdfA = p;
      x.balance = weightFromDensities(d, sp, techniques, balance, lightTracingRatio, minDistance);
      x.power = weightFromDensities(d, sp, techniques, power, lightTracingRatio, minDistance);
      x.uniform = weightFromDensities(d, sp, techniques, uniform, lightTracingRatio, minDistance);
    }
    out.push_back(x);
  }
  return out;
}

}  // namespace pathlab
