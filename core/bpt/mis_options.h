// The choice of MIS heuristic for bidirectional path tracing (a plain setting, no logic).
#pragma once

namespace pathlab {

enum class MisHeuristic { Balance, Power, Uniform };

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
  bool operator==(const MisOptions&) const = default;
};

const char* misHeuristicName(MisHeuristic h);

}  // namespace pathlab
