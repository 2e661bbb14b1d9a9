// Box-filter reduction of an image so its longer side is at most maxSide pixels (thumbnails).
#pragma once

#include "core/film/film.h"

namespace pathlab {

// Each output pixel is the mean of the input pixels whose centres fall in its footprint; an image
// already small enough is returned unchanged.
Image downsample(const Image& image, int maxSide);

}  // namespace pathlab
