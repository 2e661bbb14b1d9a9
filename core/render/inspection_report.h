// One camera sample under the magnifying glass (issue 12's "one path, every technique"): replayed
// exactly as the render computed it, every (s,t) technique tried with its contribution, weight and
// where it lands, each full path with both densities of every vertex, and that path under every
// technique of its length. As text (`render --replay`, `inspect`) and as JSON (`inspect --json`).
#pragma once

#include "core/bpt/technique_result.h"
#include "core/render/render_settings.h"
#include "core/render/sample_inspection.h"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>

namespace pathlab {

// The text `render --replay` prints; with `paths`, every technique's full path too.
void printInspection(std::ostream& out, const RenderSettings& settings, const SampleInspection& inspection, bool paths);

// The JSON of `pathlab inspect --json` (docs/cli.md, `pathlab inspect`): pixel, sample, seed,
// heuristic, the subpaths with their vertex densities, and per technique its contribution, weight,
// raster position, path (light end first, with both densities of each vertex) and the path's
// density and weights under every technique of its length.
nlohmann::json inspectionJson(const RenderSettings& settings, const SampleInspection& inspection);

}  // namespace pathlab
