// The choice of MIS heuristic for bidirectional path tracing (a plain setting, no logic).
#pragma once

#include "core/media/medium_sampling.h"

#include <optional>
#include <string_view>

namespace pathlab {

// Off: Veach's naive combination (1997, sec. 9.1): every enabled technique of length k weighs
// 1 / n_k, n_k the number enabled at that length, whatever the path. Unlike Uniform, which counts
// only the techniques able to produce the path, it is biased wherever an enabled technique cannot
// sample some path of its length (mis_off.h says where).
// VarianceAware: the balance heuristic with each technique's sample count scaled by a factor
// estimated from the earlier passes (Grittmann et al. 2019; core/bpt/variance_aware_mis.h).
// Optimal: the balance heuristic's weights plus the correction that makes them the weights of least
// variance (Kondapaneni et al. 2019), with coefficients estimated from the earlier passes
// (core/bpt/optimal_mis.h); the kernel weighs as under Balance, the render adds the correction.
enum class MisHeuristic { Balance, Power, Uniform, Off, VarianceAware, Optimal };
inline constexpr int kMisHeuristicCount = 6;

// Default of MisOptions::minConnection (fraction of the scene's bounding radius).
inline constexpr float kDefaultMinConnection = 1e-3f;

struct MisOptions {
  MisHeuristic heuristic = MisHeuristic::Balance;
  float beta = 2.f;  // exponent of the power heuristic
  // Near-coincident connections: a technique whose connection edge is shorter than minConnection
  // x the scene's bounding radius is left out of the set able to produce that path, provided an
  // enabled technique that samples the edge instead remains (misWeight). Its geometry term
  // 1/d^2 is unbounded near concave edges and corners, which gives the connection infinite
  // variance unless its weight vanishes there; balance and power weights nearly do, uniform ones
  // do not. 0 turns the exclusion off.
  float minConnection = kDefaultMinConnection;
  // The equiangular technique family E(1, k) (core/bpt/equiangular_technique.h): left out
  // (Distance), weighted beside the connections (Mis), or in place of C(1, k) on every path it can
  // sample where E(1, k) is enabled (Equiangular: C(1, k) is then unusable there, a rule on the
  // path and the technique set alone).
  MediumSampling mediumSampling = MediumSampling::Distance;
  bool operator==(const MisOptions&) const = default;
};

const char* misHeuristicName(MisHeuristic h);
// The heuristic misHeuristicName names, or nullopt.
std::optional<MisHeuristic> misHeuristicFromName(std::string_view name);
// "balance, power, uniform, off, variance-aware or optimal", for messages.
inline constexpr const char* kMisHeuristicNames = "balance, power, uniform, off, variance-aware or optimal";

}  // namespace pathlab
