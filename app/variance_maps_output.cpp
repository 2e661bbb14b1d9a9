// Files of the variance maps: EXR of the variances and of the dominant variance, PNG of the colours.
#include "app/variance_maps_output.h"

#include "app/technique_maps_output.h"
#include "core/film/image_io.h"
#include "core/maps/map_colours.h"
#include "core/maps/map_legend.h"
#include "core/render/technique_luminance.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>

namespace pathlab::app {

namespace {
std::string varianceName(Technique x) { return fmt::format("-variance{}", techniqueFileTag(x)); }
}  // namespace

std::vector<std::string> varianceMapPaths(const std::string& output, int length, TechniqueFamilies families) {
  std::vector<std::string> paths;
  for (const Technique x : techniquesUpTo(length, families)) paths.push_back(besideOutput(output, varianceName(x) + ".exr"));
  paths.push_back(besideOutput(output, "-variance.png"));
  for (const char* ext : {".exr", ".png"}) paths.push_back(besideOutput(output, std::string("-variance-dominant") + ext));
  return paths;
}

void writeVarianceMaps(const std::string& output, const RenderSession& session, int length) {
  const TechniqueLuminance variance = techniqueLuminance(session, length);
  const float largest = varianceScaleTop(variance);
  std::vector<Image> tiles(Technique::countUpTo(variance.length));
  for (const Technique x : techniquesUpTo(variance.length, variance.families)) {
    const std::vector<float>& v = variance.variance[x.index()];
    writeImage(besideOutput(output, varianceName(x) + ".exr"), grey(v, variance.width, variance.height));
    tiles[x.index()] = varianceColours(v, variance.width, variance.height, largest);
  }
  writeImage(besideOutput(output, "-variance.png"),
             displayToLinear(labelledMosaic(tiles, variance.length, variance.families)));
  // Which technique the noise comes from, and its share of the techniques' variance.
  const DominantMap m = dominantVarianceMap(variance);
  writeImage(besideOutput(output, "-variance-dominant.exr"), dominantValues(m));
  writeImage(besideOutput(output, "-variance-dominant.png"),
             displayToLinear(withDominantLegend(dominantColours(m), m, "most variance")));
}

}  // namespace pathlab::app
