// MIS off (MisHeuristic::Off): the constant weight 1 / n_k of each length, and where in a scene
// that naive combination is biased, and why.
#pragma once

#include "core/bpt/technique_set.h"
#include "core/media/medium_sampling.h"
#include "core/scene/scene.h"

#include <string>
#include <vector>

namespace pathlab {

// weights[k] = 1 / n_k for k = 1..maxLength (0 where no technique of length k is enabled);
// weights[0] is unused. Built once per settings change: the weight never depends on the path.
// With the equiangular family (mediumSampling not Distance) E(1, k) counts in n_k for k >= 2.
std::vector<float> misOffWeights(const TechniqueSet& techniques, int maxLength,
                                 MediumSampling mediumSampling = MediumSampling::Distance);

// The naive combination estimates sum_x f(x) c(x) / n_k for a path x of length k, where c(x)
// counts the enabled techniques able to sample x: biased exactly where 0 < c(x) < n_k for some
// x (c = 0 is a path no enabled technique samples, which every heuristic loses). The structural
// reasons a technique cannot sample a path in pathlab:
//  - s = 0 cannot hit a point, spot or directional light (a delta position or direction);
//  - s >= 1 cannot connect at a vertex with a delta BSDF (smooth mirror, glass, clear coat):
//    for a path of length k >= 2 with such a vertex x_i (1 <= i <= k - 1), s = i and s = i + 1;
//  - a pinhole camera biases nothing: it cannot be hit, but pathlab has no t = 0 technique, and
//    t = 1 connects to the pinhole as to a lens point.
struct MisOffBias {
  std::vector<int> lengths;          // the biased lengths, ascending
  std::vector<std::string> reasons;  // one phrase each, with the lengths it biases
  bool biased() const { return !lengths.empty(); }
};
//  - an orthographic camera cannot be connected to: t = 1 samples no path.
//  - bpt's equiangular techniques E(1, k) (mediumSampling not Distance) count at every length
//    k >= 2 where it is enabled, and sample only paths whose x1 lies in a homogeneous
//    scattering medium. (Off weighs them beside C(1, k) under `equiangular` too: the rule "in
//    place of" looks at the path, which Off does not.)
MisOffBias misOffBias(const Scene& scene, const TechniqueSet& techniques, int maxLength, bool pinhole,
                      bool orthographic = false, MediumSampling mediumSampling = MediumSampling::Distance);

// One line for the CLI warning and the viewer's status line, "" when unbiased: "mis off: lengths
// 1-10 biased (1/n_k also goes to techniques that cannot sample the path): ...".
std::string misOffWarning(const MisOffBias& bias);

// "1-3, 5, 7-10".
std::string lengthRanges(const std::vector<int>& lengths);

}  // namespace pathlab
