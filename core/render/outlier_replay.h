// An outlier (core/render/outliers.h) replayed: its camera sample traced again, the record of the
// technique that made it found in the trace, and the second half of the course notes' sentence,
// "sampled with low probability", as a number: the density of the technique that sampled its path
// over the largest density among the enabled techniques able to sample it. `pathlab outliers` and
// the viewer's outlier list both read it.
#pragma once

#include <nlohmann/json.hpp>

#include "core/image/image.h"
#include "core/render/render_settings.h"
#include "core/render/outliers.h"
#include "core/render/sample_inspection.h"

namespace pathlab {

struct ReplayedOutlier {
  Outlier o;
  SampleInspection inspection;
  int record = -1;            // index into inspection.trace.records (-1: not found again)
  double densityRatio = 0.0;  // p of the technique that sampled it / the largest counted p (0: unknown)
  Technique best;             // the technique of that largest p
};

// The record of `o` in its sample's trace: its technique's contributed record whose weighted
// luminance is nearest its own (a merge may contribute several times in one sample); -1: none.
int outlierRecord(const SampleTrace& trace, const Outlier& o);

// Replays `o`'s sample with `session`'s settings (those it was rendered with), its record found
// (outlierRecord).
ReplayedOutlier replayOutlier(const RenderSession& session, const Outlier& o);

// The share of its pixel's value in `image` (the mean of `spp` passes) that `o` gave: a camera
// sample adds its value / spp to its pixel, and so does a splat (the film divides the splats by
// the light subpaths, one a pixel a pass). 0 when the pixel is black or off the image.
double outlierShareOfPixel(const Outlier& o, const Image& image, uint64_t spp);

// One entry of the list `pathlab outliers --json` writes (and Python's Renderer.outliers()):
// luminance, value, pixel, sample, technique, raster, shareOfPixel, densityRatio, bestTechnique,
// and record, the technique's record as `inspect --json` writes it. `settings`: the render's.
nlohmann::json outlierJson(const RenderSettings& settings, const ReplayedOutlier& r, double shareOfPixel);

}  // namespace pathlab
