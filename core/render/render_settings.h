// Everything that changes the estimate. The viewer edits a copy; a difference from the active
// settings (defaulted operator==) starts a new generation of the film.
#pragma once

#include "core/bpt/mis_options.h"
#include "core/camera/camera.h"

#include <cstdint>
#include <string>

namespace pathlab {

// Pt: the path tracer; Bpt: bidirectional; Lt: bidirectional restricted to t = 1 (light tracing).
enum class IntegratorKind { Pt, Bpt, Lt };

struct RenderSettings {
  int width = 512;
  int height = 512;
  int maxLength = 10;            // maximum path length in edges (a visible emitter is 1)
  bool russianRoulette = true;   // starts at kRussianRouletteStart edges
  uint64_t seed = 0;
  IntegratorKind integrator = IntegratorKind::Pt;
  LensOptions lens;
  std::string techniques = "all";  // TechniqueSet SPEC (core/bpt/technique_set.h), Bpt and Lt only
  MisOptions mis;

  bool operator==(const RenderSettings&) const = default;
};

inline constexpr int kRussianRouletteStart = 3;

const char* integratorName(IntegratorKind kind);

}  // namespace pathlab
