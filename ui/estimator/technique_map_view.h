// The viewer's technique map display: which map is shown (dominant technique of every length or
// of one, share of a technique, where a technique cannot sample) and its colours, computed from
// the luminances the renderer publishes (ProgressiveRenderer::techniqueMaps). Choosing another
// map never restarts the image; only the maps' length (the pyramid's) does.
#pragma once

#include "core/film/film.h"
#include "core/maps/technique_maps.h"

#include <string>

namespace pathlab::ui {

// Variance: a technique's variance of a pass's estimate (log scale); VarianceDominant: the technique
// with the most variance (issue 34, "where the noise comes from").
enum class MapKind { Dominant, Share, CannotSample, Variance, VarianceDominant };

struct MapView {
  bool show = false;
  MapKind kind = MapKind::Dominant;
  int length = 3;          // the techniques covered (the pyramid's length while the maps are shown)
  int dominantLength = 0;  // 0: dominant over every length up to `length`
  Technique technique{1, 2};
  bool operator==(const MapView&) const = default;
};

// The display colours (map_colours.h) of the chosen map; empty when `lum` holds nothing yet.
// A chosen length or technique beyond lum.length is clamped to it.
Image mapImage(const TechniqueLuminance& lum, const MapView& view);

// `view --technique-map`: "dominant", "dominant:K", "share:S,T", "cannot:S,T", "variance:S,T" or
// "variance-dominant" (MS,T for a merge: "share:M2,3"); throws
// std::invalid_argument naming the text otherwise.
MapView parseMapView(const std::string& text);
// What the caption says of a shown map: "dominant technique, lengths 1-3", "share of (1,2)", ...
std::string mapViewName(const MapView& view);

}  // namespace pathlab::ui
