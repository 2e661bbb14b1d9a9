// Colouring the chosen technique map; parsing `view --technique-map`.
#include "ui/estimator/technique_map_view.h"

#include "core/maps/map_colours.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace pathlab::ui {

Image mapImage(const TechniqueLuminance& lum, const MapView& view) {
  if (lum.length < 1 || lum.weighted.empty()) return {};
  Technique x = view.technique;
  if (!x.valid() || x.length() > lum.length) x = Technique{std::min(1, lum.length - 1), lum.length};
  switch (view.kind) {
    case MapKind::Dominant: return dominantColours(dominantMap(lum, std::clamp(view.dominantLength, 0, lum.length)));
    case MapKind::Share: return shareColours(shareMap(lum, x), lum.width, lum.height);
    case MapKind::CannotSample:
      if (lum.sampleable.empty()) return {};
      return cannotSampleColours(cannotSampleMap(lum, x));
  }
  return {};
}

MapView parseMapView(const std::string& text) {
  MapView v;
  v.show = true;
  int a = 0, b = 0;
  char extra = 0;
  if (text == "dominant") return v;
  if (std::sscanf(text.c_str(), "dominant:%d%c", &a, &extra) == 1 && a >= 1) {
    v.dominantLength = a;
    v.length = std::max(v.length, a);
    return v;
  }
  for (const auto& [prefix, kind] : {std::pair{"share:%d,%d%c", MapKind::Share}, std::pair{"cannot:%d,%d%c", MapKind::CannotSample}})
    if (std::sscanf(text.c_str(), prefix, &a, &b, &extra) == 2 && Technique{a, b}.valid()) {
      v.kind = kind;
      v.technique = Technique{a, b};
      v.length = std::max(v.length, v.technique.length());
      return v;
    }
  throw std::invalid_argument("--technique-map: '" + text +
                              "' is not dominant, dominant:K, share:S,T or cannot:S,T");
}

std::string mapViewName(const MapView& v) {
  switch (v.kind) {
    case MapKind::Dominant:
      return v.dominantLength > 0 ? fmt::format("dominant technique of length {}", v.dominantLength)
                                  : fmt::format("dominant technique, lengths 1-{}", v.length);
    case MapKind::Share: return fmt::format("share of ({},{})", v.technique.s, v.technique.t);
    case MapKind::CannotSample: return fmt::format("where ({},{}) cannot sample", v.technique.s, v.technique.t);
  }
  return "technique map";
}

}  // namespace pathlab::ui
