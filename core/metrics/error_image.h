// Per-pixel error against a reference, one value a pixel: what the viewer's false-colour error
// view shows (shaders/display.frag computes the same on the GPU; this is its reference and the
// source of the colour bar's automatic range).
#pragma once

#include "core/film/film.h"

#include <vector>

namespace pathlab {

// RelativeSquared: the mean over the pixel's three channels of (x − r)² / (r² + kRelMseEpsilon),
// so the image's mean is exactly relMSE (error_metrics.h). Absolute: the mean of |x − r|.
enum class PixelError { RelativeSquared, Absolute };

const char* pixelErrorName(PixelError kind);

// Throws std::invalid_argument when the sizes differ. Row-major, top row first.
std::vector<float> pixelErrors(const Image& image, const Image& reference, PixelError kind);

// The [lo, hi] quantiles (in [0, 1]) of the positive finite values, for a colour bar that spans
// what the image holds; {0, 0} when there is none.
std::pair<float, float> positiveQuantiles(std::vector<float> values, double lo, double hi);

}  // namespace pathlab
