// Box-filter reduction of an image so its longer side is at most maxSide pixels, and the
// technique pyramid reduced that way to the thumbnails the viewer shows.
#pragma once

#include "core/film/film.h"
#include "core/sampling/technique.h"

#include <functional>
#include <vector>

namespace pathlab {

// Each output pixel is the mean of the input pixels whose centres fall in its footprint; an image
// already small enough is returned unchanged.
Image downsample(const Image& image, int maxSide);

// Technique (s, t) of a pyramid (Veach 1997, fig. 10.3), its weighted and unweighted images
// downsampled.
struct TechniqueThumbnail {
  int s = 0, t = 1;
  TechniqueKind kind = TechniqueKind::Connection;
  Technique technique() const { return Technique{s, t, kind}; }
  Image weighted, unweighted;
};

// Every technique of `families` up to maxLength in Technique::index() order, the weighted then the unweighted
// image(technique, unweighted) of each downsampled to at most maxSide pixels on the longer side.
using TechniqueImageSource = std::function<Image(Technique technique, bool unweighted)>;
std::vector<TechniqueThumbnail> techniqueThumbnails(int maxLength, int maxSide, const TechniqueImageSource& image,
                                                    TechniqueFamilies families = TechniqueFamilies::Connections);

}  // namespace pathlab
