// Colouring the chosen technique map; parsing `view --technique-map`.
#include "ui/estimator/technique_map_view.h"

#include "core/maps/map_colours.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace pathlab::ui {

Image mapImage(const TechniqueLuminance& lum, const MapView& view) {
  if (lum.length < 1 || lum.weighted.empty()) return {};
  Technique x = view.technique;
  // A merge chosen while the pyramid keeps none (bpt without merges) falls back like a length.
  if (!x.valid() || x.length() > lum.length || !lum.has(x)) x = Technique{std::min(1, lum.length - 1), lum.length};
  switch (view.kind) {
    case MapKind::Dominant: return dominantColours(dominantMap(lum, std::clamp(view.dominantLength, 0, lum.length)));
    case MapKind::Share: return shareColours(shareMap(lum, x), lum.width, lum.height);
    case MapKind::CannotSample:
      if (lum.sampleable.empty()) return {};
      return cannotSampleColours(cannotSampleMap(lum, x));
    case MapKind::Variance:
      if (lum.variance.empty()) return {};
      return varianceColours(lum.variance[x.index()], lum.width, lum.height, varianceScaleTop(lum));
    case MapKind::VarianceDominant:
      if (lum.variance.empty()) return {};
      return dominantColours(dominantVarianceMap(lum));
  }
  return {};
}

MapView parseMapView(const std::string& text) {
  MapView v;
  v.show = true;
  int a = 0, b = 0;
  char extra = 0;
  if (text == "dominant") return v;
  if (text == "variance-dominant") {
    v.kind = MapKind::VarianceDominant;
    return v;
  }
  if (std::sscanf(text.c_str(), "dominant:%d%c", &a, &extra) == 1 && a >= 1) {
    v.dominantLength = a;
    v.length = std::max(v.length, a);
    return v;
  }
  for (const auto& [prefix, kind] : {std::pair{"share:", MapKind::Share}, std::pair{"cannot:", MapKind::CannotSample},
                                     std::pair{"variance:", MapKind::Variance}}) {
    const std::string p = prefix;
    if (text.compare(0, p.size(), p) != 0) continue;
    // S,T a connection, MS,T a merge, E1,T an equiangular technique (as --techniques writes them).
    const bool merge = text.size() > p.size() && (text[p.size()] == 'M' || text[p.size()] == 'm');
    const bool equiangular = text.size() > p.size() && (text[p.size()] == 'E' || text[p.size()] == 'e');
    const std::string rest = text.substr(p.size() + (merge || equiangular ? 1 : 0));
    if (std::sscanf(rest.c_str(), "%d,%d%c", &a, &b, &extra) != 2) break;
    const Technique x{a, b, merge ? TechniqueKind::Merge : equiangular ? TechniqueKind::Equiangular : TechniqueKind::Connection};
    if (!x.valid()) break;
    v.kind = kind;
    v.technique = x;
    v.length = std::max(v.length, v.technique.length());
    return v;
  }
  throw std::invalid_argument("--technique-map: '" + text +
                              "' is not dominant, dominant:K, share:S,T, share:MS,T, share:E1,T, cannot:S,T, "
                              "cannot:MS,T, cannot:E1,T, variance:S,T, variance:MS,T, variance:E1,T or variance-dominant");
}

std::string mapViewName(const MapView& v) {
  switch (v.kind) {
    case MapKind::Dominant:
      return v.dominantLength > 0 ? fmt::format("dominant technique of length {}", v.dominantLength)
                                  : fmt::format("dominant technique, lengths 1-{}", v.length);
    case MapKind::Share: return "share of " + techniqueLabel(v.technique);
    case MapKind::CannotSample: return "where " + techniqueLabel(v.technique) + " cannot sample";
    case MapKind::Variance: return "variance of " + techniqueLabel(v.technique);
    case MapKind::VarianceDominant: return fmt::format("most variance, lengths 1-{}", v.length);
  }
  return "technique map";
}

}  // namespace pathlab::ui
