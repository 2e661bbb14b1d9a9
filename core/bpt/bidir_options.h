// What the bidirectional tracer needs to know of the render settings, and nothing else: the
// estimator (techniques, heuristic, isolation, length) and which outputs it feeds.
#pragma once

#include "core/bpt/mis_options.h"
#include "core/bpt/technique_set.h"

#include <optional>
#include <string>

namespace pathlab {

// One technique shown alone. Weighted: its MIS-weighted share among the enabled techniques (the
// shares of all enabled techniques sum to the full image). Unweighted: its own estimate of every
// path of length s + t - 1 it can sample (weight 1).
struct Isolation {
  int s = 0, t = 1;
  bool unweighted = false;
  TechniqueKind kind = TechniqueKind::Connection;  // Merge: M(s, t); Equiangular: E(1, t)
  Technique technique() const { return Technique{s, t, kind}; }
  bool operator==(const Isolation&) const = default;
};
// "S,T", "MS,T" (a merge) or "E1,T" (an equiangular technique), weighted; throws std::invalid_argument naming the text otherwise. The
// technique's range is the caller's to check (it depends on the maximum length).
Isolation parseIsolation(const std::string& text);

// A deliberate bug for teaching and for testing the consistency check (issue 13): technique
// (s, t)'s unweighted contribution is multiplied by `factor`, so it and the image are biased. A
// merge M(s, t) with kind Merge (factor 2: its density estimate's normalisation doubled).
struct BiasInjection {
  int s = 0, t = 1;
  float factor = 1.f;
  TechniqueKind kind = TechniqueKind::Connection;
  Technique technique() const { return Technique{s, t, kind}; }
  bool operator==(const BiasInjection&) const = default;
};

// How a sample's techniques get their subpaths. All: one camera and one light subpath, every
// prefix pair connected (path reuse, Veach 1997 sec. 10.2). Endpoints: each technique (s, t)
// samples a light subpath of exactly s and a camera subpath of exactly t vertices of its own and
// connects their endpoints (naive BPT): the same techniques, weights and expectation, more rays.
enum class ConnectStrategy { All, Endpoints };
const char* connectStrategyName(ConnectStrategy c);

// Where a camera subpath merges: at every vertex that can be merged (vertex connection and
// merging, bidirectional photon mapping), or only at its first one that is not a delta scatter,
// its "first diffuse hit" (progressive photon mapping). A path then has at most one merge able to
// sample it, the one at that vertex; the weights count no other (merge_mis.h).
enum class MergeSite { Every, FirstNonSpecular };
const char* mergeSiteName(MergeSite m);

struct BidirOptions {
  int maxLength = 10;           // edges
  bool russianRoulette = true;  // sampling/russian_roulette.h
  TechniqueSet techniques;      // the enabled set: MIS weights are normalised over it
  MisOptions mis;
  std::optional<Isolation> isolate;
  int pyramidLength = 0;  // > 0: every technique up to this length also goes to the pyramid
  bool checkMis = false;  // test every weighted path's partition of unity (Counters)
  ConnectStrategy connect = ConnectStrategy::All;
  std::optional<BiasInjection> injectBias;
  MergeSite mergeSite = MergeSite::Every;
  float lightPaths = 1.f;  // light subpaths per camera sample (core/bpt/light_paths.h)
};

}  // namespace pathlab
