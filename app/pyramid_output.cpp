// Per-technique images and mosaics of the technique pyramid.
#include "app/pyramid_output.h"

#include "core/sampling/technique_label.h"

#include "core/film/image_io.h"
#include "core/maps/map_legend.h"
#include "core/sampling/technique.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace pathlab::app {

namespace {

std::string techniquePath(const std::filesystem::path& out, Technique x, bool unweighted) {
  std::filesystem::path p = out;
  p.replace_filename(fmt::format("{}{}{}{}", out.stem().string(), techniqueFileTag(x), unweighted ? "-unweighted" : "",
                                 out.extension().string()));
  return p.string();
}

std::string mosaicPath(const std::filesystem::path& out, bool unweighted) {
  std::filesystem::path p = out;
  p.replace_filename(fmt::format("{}-pyramid{}.png", out.stem().string(), unweighted ? "-unweighted" : ""));
  return p.string();
}

}  // namespace

std::vector<std::string> pyramidPaths(const std::string& output, int length, TechniqueFamilies families) {
  std::vector<std::string> paths;
  for (const Technique x : techniquesUpTo(length, families))
    for (bool unweighted : {false, true}) paths.push_back(techniquePath(output, x, unweighted));
  paths.push_back(mosaicPath(output, false));
  paths.push_back(mosaicPath(output, true));
  return paths;
}

Image techniqueMosaic(const std::vector<Image>& tiles, int length, int gap, float background, float labelValue) {
  const auto first = std::find_if(tiles.begin(), tiles.end(), [](const Image& t) { return t.width > 0; });
  if (first == tiles.end()) return {};
  const int w = first->width, h = first->height;
  // Columns: the slots of the longest row, k + 1 connections and, when any merge tile is there,
  // k - 1 merges after them.
  // Then, when any E(1, k) tile is there, one column of them.
  bool merges = false, equiangular = false;
  for (const Technique x : techniquesUpTo(length, TechniqueFamilies::Merges))
    merges = merges || (x.index() < tiles.size() && tiles[x.index()].width > 0);
  for (const Technique x : techniquesUpTo(length, TechniqueFamilies::Equiangular))
    equiangular = equiangular || (x.index() < tiles.size() && tiles[x.index()].width > 0);
  const int columns = (merges ? 2 * length : length + 1) + (equiangular ? 1 : 0);
  Image m;
  m.width = columns * w + (columns + 1) * gap;
  m.height = length * h + (length + 1) * gap;
  m.rgb.assign(3 * static_cast<size_t>(m.width) * static_cast<size_t>(m.height), background);
  for (const Technique tx : techniquesUpTo(length, TechniqueFamilies::All)) {
    if (tx.index() >= tiles.size() || tiles[tx.index()].width <= 0) continue;
    const Image& tile = tiles[tx.index()];
    const int x0 = gap + mosaicColumn(tx, length, merges) * (w + gap), y0 = gap + (tx.length() - 1) * (h + gap);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const Vec3 v = tile.at(x, y);
        const size_t o = 3 * (static_cast<size_t>(y0 + y) * static_cast<size_t>(m.width) + static_cast<size_t>(x0 + x));
        m.rgb[o] = v.r;
        m.rgb[o + 1] = v.g;
        m.rgb[o + 2] = v.b;
      }
    // "(s,t) k=K" in the tile's top-left corner on a dark box, a font pixel per 80 tile pixels.
    if (labelValue > 0.f) {
      const std::string label = fmt::format("{} k={}", techniqueLabel(tx), tx.length());
      const int scale = std::clamp(w / 80, 1, 4);
      const int textWidth = drawText(m, -10000, -10000, label, Vec3(0.f), scale);  // measures only
      fillRect(m, x0, y0, std::min(textWidth + 4 * scale, w), std::min(9 * scale, h), Vec3(0.f));
      drawText(m, x0 + 2 * scale, y0 + scale, label, Vec3(labelValue), scale);
    }
  }
  return m;
}

void writePyramid(const std::string& output, const RenderSession& session, float exposure, int length) {
  const std::filesystem::path out(output);
  for (bool unweighted : {false, true}) {
    std::vector<Image> tiles(Technique::countUpTo(length));
    for (const Technique x : techniquesUpTo(length, session.pyramidFamilies())) {
      tiles[x.index()] = session.techniqueImage(x, unweighted);
      writeImage(techniquePath(out, x, unweighted), tiles[x.index()], exposure);
    }
    // Labels white after the PNG's exposure.
    writeImage(mosaicPath(out, unweighted), techniqueMosaic(tiles, length, 4, 0.02f, std::exp2(-exposure)), exposure);
  }
}

}  // namespace pathlab::app
