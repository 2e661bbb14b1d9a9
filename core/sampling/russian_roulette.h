// Where Russian roulette starts, shared by the path tracer and the bidirectional walks so that
// their paths of a given length are terminated by the same rule.
#pragma once

namespace pathlab {

// Edges a path has before roulette may end it (path_tracer.cpp, subpath.cpp).
inline constexpr int kRussianRouletteStart = 3;

}  // namespace pathlab
