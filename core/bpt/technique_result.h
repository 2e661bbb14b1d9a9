// What one technique (s, t) gave for one camera sample: the bidirectional kernel's result, which
// the outputs (film, pyramid, replay trace, counters) consume (sample_outputs.h).
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/math/types.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// One technique of a path's length, seen from a path another technique sampled (the path
// inspector's "one path, every technique"; techniquesOnPath, path_techniques.h).
struct TechniqueOnPath {
  int s = 0, t = 1;
  TechniqueKind kind = TechniqueKind::Connection;
  Technique technique() const { return Technique{s, t, kind}; }
  bool possible = false;  // the technique can sample this path (sampleableTechniques)
  bool enabled = false;
  // p_{s',t'}(x) in area measure: the product over the path's vertices of the density each was
  // sampled with from its own side (x_0..x_{s'-1} from the light, the rest from the camera); a
  // delta vertex counts one (its delta cancels between the techniques that share it). Zero when
  // impossible.
  double pdfA = 0.0;
  // The edge the technique connects deterministically, x_{s'-1} -- x_{s'} (none for s' = 0: the
  // camera subpath hits the emitter): its geometry term and the BSDFs at its ends are the factors
  // of f this technique does not importance-sample. A merge connects no edge (-1).
  int connectionEdge = -1;
  // A merge M(s', t'): the vertex x_{s'-1} it takes from both subpaths (-1 for a connection). Its
  // pdfA is the connection C(s')'s times the acceptance probability pi r^2 pFromCamera(x_{s'-1}),
  // and its sample count is the pass's light subpaths N (merge_mis.h: n p = eta pFromCamera p_C).
  int mergedVertex = -1;
  // In the weights' denominators: enabled, possible, and not left out by the near-coincident
  // connection rule (MisOptions::minConnection). Under balance w_s = p_s / sum of the counted p
  // (times the light-tracing sample ratio for t' = 1), power with p^beta, uniform 1 / count.
  bool counted = false;
  double balance = 0.0, power = 0.0, uniform = 0.0;  // MIS weights among the enabled techniques
  // Variance-aware MIS (variance_aware_mis.h): the factor c that multiplied this technique's count
  // where the path lands, and the weight with every technique's factor (the balance weight when
  // no factors were given: all 1).
  double factor = 1.0, varianceAware = 0.0;
};

// The entry of `every` (techniquesOnPath's list) for technique x, or null when it is not listed.
inline const TechniqueOnPath* findOnPath(const std::vector<TechniqueOnPath>& every, Technique x) {
  for (const TechniqueOnPath& e : every)
    if (e.technique() == x) return &e;
  return nullptr;
}

// The full path a technique formed, light end first (x_0 on the light ... x_{k} at the camera), as
// the replay trace keeps it for the path inspector: where each vertex is, what it is, and the
// area density of each vertex sampled from either side (PathDensities, mis.h), so every
// technique's p_{s',t'} = prod_{i<s'} pFromLight[i] * prod_{i>=s'} pFromCamera[i] (a delta
// vertex's density counts one; x0Nee in place of pFromLight[0] for s' = 1) can be recomputed from it.
enum class TracedVertexKind : uint8_t { Camera, Light, Surface, Medium };
struct TracedPath {
  std::vector<Vec3> p;
  std::vector<TracedVertexKind> kind;
  std::vector<uint8_t> delta;           // a delta BSDF lobe scattered here
  std::vector<uint8_t> deltaPosition;   // a point / spot light or a pinhole: cannot be hit
  std::vector<double> pFromLight, pFromCamera;
  // x0's density under technique (1, n - 1) for n >= 3 (PathDensities::x0Nee): next-event
  // estimation chose its light for x1. pFromLight[0] otherwise, and in scenes that choose by power.
  double x0Nee = 0.0;
  size_t size() const { return p.size(); }
};

enum class TechniqueOutcome : uint8_t {
  Zero,         // cannot form the path (delta vertex, f = 0, off the film), or weight zero and not wanted
  Blocked,      // a non-zero contribution whose shadow ray was occluded
  Contributed,  // unoccluded, non-zero (possibly invalid: NaN, Inf, negative)
};

// A merge M(s, t)'s two vertices: the light subpath's y(s-1) and the camera subpath's z(t-1),
// closer than the pass's radius, taken as one (the path runs through y(s-1) then z(t-2)); the
// density estimate's disk of radius r is centred on z(t-1), in its surface's plane (normal: its
// geometric normal).
struct MergedVertices {
  Vec3 light{0.f}, camera{0.f}, cameraNormal{0.f};
  float radius = 0.f;
};

struct TechniqueResult {
  int s = 0, t = 1;
  TechniqueKind kind = TechniqueKind::Connection;
  Technique technique() const { return Technique{s, t, kind}; }
  TechniqueOutcome outcome = TechniqueOutcome::Zero;
  Spectrum unweighted{0.f};  // connect(s, t)'s contribution (zero unless Contributed)
  float weight = 0.f;        // its MIS weight among the enabled techniques (0 if disabled)
  // The factor the image applies: weight, 1 for the isolated technique shown unweighted, 0 when
  // the technique is not in the image.
  float imageWeight = 0.f;
  Vec2 pRaster{0.f};       // where it lands: the sample's own pixel, or the splat position (t = 1)
  bool inImage = false;    // reaches the image (enabled, or the isolated technique)
  bool inPyramid = false;  // goes to the technique pyramid
  MergedVertices merged;   // a merge's (kind Merge), for the replay trace; zero for a connection
  // Contributed results, when an output asks (SampleOutputs::wantsSampleable): bit r set when the
  // technique at slot r of this length (Technique::slot(); r = s' for the connection (s', k + 1 - s'))
  // could have sampled this same path (sampleableTechniques, mis.h).
  uint64_t sampleableBy = 0;
  // With sampleableBy: p_{r} / p_{own} of this path for every slot r of its length
  // (techniqueDensityRatios, mis.h), in the kernel's scratch; valid only while the outputs consume it.
  const double* densityRatios = nullptr;
  // Contributed results, when an output asks: the sum of the weights of the path's techniques that
  // walk a light subpath (lightWalkWeight, mis.h; --light-paths auto's w_L).
  double lightWalkWeight = 0.0;
  // Contributed connections, when an output asks: the balance heuristic's weight of every technique
  // of the path's length by slot (balanceWeights, mis.h; optimal MIS), in the kernel's scratch;
  // valid only while the outputs consume the result.
  const double* balanceWeights = nullptr;
  // With balanceWeights: what the MIS densities leave out of the decisions that made the path's two
  // prefixes, relative to a function of the path alone (PathVertex::omittedFactor of x(s-1) and
  // z(t-1)), by which optimal MIS scales its correction.
  float omittedFactor = 1.f;
  // For the replay trace: this path under every technique of its length (techniquesOnPath), by
  // slot, in the kernel's scratch; valid only while the outputs consume the result.
  const std::vector<TechniqueOnPath>* onPath = nullptr;
  // For the replay trace: the path this technique formed (also when blocked), in the kernel's
  // scratch; null when it formed none or no output asked.
  const TracedPath* traced = nullptr;
  bool blocked() const { return outcome == TechniqueOutcome::Blocked; }
};

// Every technique of one replayed sample (`pathlab render --replay`).
struct SampleTrace {
  int cameraVertices = 0, lightVertices = 0;
  std::vector<TechniqueResult> records;  // every technique tried, in evaluation order (scratch pointers null)
  // records[i]'s path under every technique of its length (empty unless it contributed).
  std::vector<std::vector<TechniqueOnPath>> onPath;
  // records[i]'s full path (empty when the technique formed none: a delta vertex, off the film).
  std::vector<TracedPath> paths;
  // The shared subpaths, camera vertex 0 at the lens and light vertex 0 on the emitter, with the
  // densities they were created with (path reuse; empty under ConnectStrategy::Endpoints, where
  // each technique walks its own, kept in `paths`).
  std::vector<PathVertex> cameraSubpath, lightSubpath;
};

}  // namespace pathlab
