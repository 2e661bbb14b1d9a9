// The choice of MIS heuristic for bidirectional path tracing (a plain setting, no logic).
#pragma once

namespace pathlab {

enum class MisHeuristic { Balance, Power, Uniform };

struct MisOptions {
  MisHeuristic heuristic = MisHeuristic::Balance;
  float beta = 2.f;  // exponent of the power heuristic
  bool operator==(const MisOptions&) const = default;
};

const char* misHeuristicName(MisHeuristic h);

}  // namespace pathlab
