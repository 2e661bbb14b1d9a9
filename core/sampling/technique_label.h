// How a technique is written for people and in file names, the same in every report, legend and
// panel: "(s,t)" for a connection, "M(s,t)" for a merge, "E(1,t)" for the equiangular technique.
#pragma once

#include "core/sampling/technique.h"

#include <string>

namespace pathlab {

inline std::string techniqueLabel(Technique x) {
  return (x.isMerge() ? "M(" : x.isEquiangular() ? "E(" : "(") + std::to_string(x.s) + "," + std::to_string(x.t) + ")";
}

// The part of a file name that names the technique: "-s2-t3", "-m-s2-t3" for a merge, "-e-s1-t3"
// for the equiangular technique.
inline std::string techniqueFileTag(Technique x) {
  return (x.isMerge() ? "-m-s" : x.isEquiangular() ? "-e-s" : "-s") + std::to_string(x.s) + "-t" + std::to_string(x.t);
}

}  // namespace pathlab
