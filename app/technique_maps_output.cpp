// Files of the technique maps: EXR of the values, PNG of the colours with their legends.
#include "app/technique_maps_output.h"

#include "core/sampling/technique_label.h"

#include "app/pyramid_output.h"
#include "core/film/image_io.h"
#include "core/maps/map_colours.h"
#include "core/maps/map_legend.h"
#include "core/render/technique_luminance.h"

#include <fmt/core.h>

#include <filesystem>

namespace pathlab::app {

namespace {

std::string dominantName(int k) { return k > 0 ? fmt::format("-dominant-k{}", k) : "-dominant"; }
std::string techniqueName(const char* what, Technique x) { return fmt::format("-{}{}", what, techniqueFileTag(x)); }

Image blank(int width, int height) {
  return Image{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height), 0.f)};
}

// The EXR of the cannot-sample map: (fraction it cannot sample, share of its length's image, Reach
// as 0 empty, 1 impossible, 2 weighted away, 3 sampled); -1 in the first two without light.
Image cannotSampleValues(const CannotSampleMap& m) {
  Image img = blank(m.width, m.height);
  for (size_t i = 0; i < m.reach.size(); ++i) {
    img.rgb[3 * i] = m.unreachable[i];
    img.rgb[3 * i + 1] = m.shareOfLength[i];
    img.rgb[3 * i + 2] = static_cast<float>(m.reach[i]);
  }
  return img;
}

}  // namespace

std::string besideOutput(const std::string& output, const std::string& suffix) {
  std::filesystem::path p(output);
  p.replace_filename(std::filesystem::path(output).stem().string() + suffix);
  return p.string();
}

Image dominantValues(const DominantMap& m) {
  Image img = blank(m.width, m.height);
  for (size_t i = 0; i < m.technique.size(); ++i) {
    const int x = m.technique[i];
    const Technique tx = x >= 0 ? Technique::fromIndex(static_cast<size_t>(x)) : Technique{x, x};
    img.rgb[3 * i] = static_cast<float>(tx.s);
    // A merge as (s, -t), s >= 2; an equiangular technique E(1, t) as (1, -t).
    img.rgb[3 * i + 1] = static_cast<float>(x >= 0 && (tx.isMerge() || tx.isEquiangular()) ? -tx.t : tx.t);
    img.rgb[3 * i + 2] = m.share[i];
  }
  return img;
}

Image grey(const std::vector<float>& v, int width, int height) {
  Image img = blank(width, height);
  for (size_t i = 0; i < v.size(); ++i) img.rgb[3 * i] = img.rgb[3 * i + 1] = img.rgb[3 * i + 2] = v[i];
  return img;
}

Image labelledMosaic(const std::vector<Image>& tiles, int length, TechniqueFamilies families) {
  constexpr int kGap = 4;
  Image m = techniqueMosaic(tiles, length, kGap, 0.12f);
  const int w = tiles.front().width, h = tiles.front().height;
  for (const Technique x : techniquesUpTo(length, families)) {
    const int x0 = kGap + mosaicColumn(x, length, covers(families, TechniqueKind::Merge)) * (w + kGap) + 3,
              y0 = kGap + (x.length() - 1) * (h + kGap) + 3;
    const std::string label = techniqueLabel(x);
    drawText(m, x0 + 1, y0 + 1, label, Vec3(0.f));
    drawText(m, x0, y0, label, Vec3(1.f));
  }
  return m;
}

std::vector<std::string> techniqueMapPaths(const std::string& output, int length, TechniqueFamilies families) {
  std::vector<std::string> paths;
  for (int k = 0; k <= length; ++k)
    for (const char* ext : {".exr", ".png"}) paths.push_back(besideOutput(output, dominantName(k) + ext));
  for (const char* what : {"share", "cannot"})
    for (const Technique x : techniquesUpTo(length, families))
      paths.push_back(besideOutput(output, techniqueName(what, x) + ".exr"));
  paths.push_back(besideOutput(output, "-share.png"));
  paths.push_back(besideOutput(output, "-cannot-sample.png"));
  if (covers(families, TechniqueKind::Merge))
    for (const char* ext : {".exr", ".png"}) paths.push_back(besideOutput(output, std::string("-share-merges") + ext));
  return paths;
}

void writeTechniqueMaps(const std::string& output, const RenderSession& session, int length) {
  const TechniqueLuminance lum = techniqueLuminance(session, length);
  for (int k = 0; k <= length; ++k) {
    const DominantMap m = dominantMap(lum, k);
    writeImage(besideOutput(output, dominantName(k) + ".exr"), dominantValues(m));
    const std::string title = k > 0 ? fmt::format("length {}", k) : fmt::format("lengths 1-{}", length);
    writeImage(besideOutput(output, dominantName(k) + ".png"),
               displayToLinear(withDominantLegend(dominantColours(m), m, title)));
  }
  std::vector<Image> shares(Technique::countUpTo(length)), cannot(shares.size());
  for (const Technique x : techniquesUpTo(length, lum.families)) {
    const std::vector<float> share = shareMap(lum, x);
    writeImage(besideOutput(output, techniqueName("share", x) + ".exr"), grey(share, lum.width, lum.height));
    shares[x.index()] = shareColours(share, lum.width, lum.height);
    const CannotSampleMap c = cannotSampleMap(lum, x);
    writeImage(besideOutput(output, techniqueName("cannot", x) + ".exr"), cannotSampleValues(c));
    cannot[x.index()] = cannotSampleColours(c);
  }
  writeImage(besideOutput(output, "-share.png"),
             displayToLinear(withShareBar(labelledMosaic(shares, length, lum.families), "of the image", false)));
  writeImage(besideOutput(output, "-cannot-sample.png"),
             displayToLinear(withShareBar(labelledMosaic(cannot, length, lum.families), "of its length", true)));
  if (covers(lum.families, TechniqueKind::Merge)) {
    // Every merge together: where vertex merging carries the image.
    const std::vector<float> share = familyShareMap(lum, TechniqueKind::Merge);
    writeImage(besideOutput(output, "-share-merges.exr"), grey(share, lum.width, lum.height));
    writeImage(besideOutput(output, "-share-merges.png"),
               displayToLinear(withShareBar(shareColours(share, lum.width, lum.height), "merges' share", false)));
  }
}

}  // namespace pathlab::app
