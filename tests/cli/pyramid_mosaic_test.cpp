// The pyramid mosaic's labels (issue 14: every cell carries its (s,t) and k): drawn in each
// tile's top-left corner at the value asked for, nowhere else; none without a label value.
#include "app/pyramid_output.h"

#include <gtest/gtest.h>

namespace pathlab::app {
namespace {

TEST(PyramidMosaic, EveryTileCarriesItsLabelInItsCorner) {
  const int length = 3, w = 160, h = 120, gap = 4;
  std::vector<Image> tiles(Technique::countUpTo(length));  // by Technique::index(), merges left empty
  for (const Technique x : techniquesUpTo(length)) tiles[x.index()] = Image{w, h, std::vector<float>(3 * w * h, 0.5f)};
  const Image plain = techniqueMosaic(tiles, length, gap, 0.02f);
  const Image labelled = techniqueMosaic(tiles, length, gap, 0.02f, 7.f);
  ASSERT_EQ(plain.width, labelled.width);
  for (const Technique x : techniquesUpTo(length)) {
    const int x0 = gap + x.s * (w + gap), y0 = gap + (x.length() - 1) * (h + gap);
    int text = 0, changedOutside = 0;
    for (int y = y0; y < y0 + h; ++y)
      for (int px = x0; px < x0 + w; ++px) {
        const float v = labelled.at(px, y).r;
        const bool corner = y < y0 + 20;  // the label band along the tile's top (18 pixels at this size)
        text += v == 7.f ? 1 : 0;
        changedOutside += (!corner && v != plain.at(px, y).r) ? 1 : 0;
      }
    EXPECT_GT(text, 30) << "(" << x.s << "," << x.t << ") has no label";
    EXPECT_EQ(changedOutside, 0) << "(" << x.s << "," << x.t << ")";
  }
  for (float v : plain.rgb) ASSERT_NE(v, 7.f);
}

TEST(PyramidMosaic, MergesTakeTheColumnsAfterTheirLengthsConnections) {
  const int length = 3, w = 160, h = 120, gap = 4;
  std::vector<Image> tiles(Technique::countUpTo(length));
  for (const Technique x : techniquesUpTo(length, TechniqueFamilies::Connections | TechniqueFamilies::Merges))
    tiles[x.index()] = Image{w, h, std::vector<float>(3 * w * h, x.isMerge() ? 0.25f : 0.5f)};
  const Image m = techniqueMosaic(tiles, length, gap, 0.02f);
  EXPECT_EQ(m.width, 2 * length * w + (2 * length + 1) * gap);  // 4 connections + 2 merges in row 3
  for (const Technique x : techniquesUpTo(length, TechniqueFamilies::Connections | TechniqueFamilies::Merges)) {
    const int x0 = gap + x.slot() * (w + gap), y0 = gap + (x.length() - 1) * (h + gap);
    EXPECT_EQ(m.at(x0 + w / 2, y0 + h / 2).r, x.isMerge() ? 0.25f : 0.5f) << x.s << "," << x.t;
  }
  // Row 2 has one merge (slot 3): slots 4 and 5 of it are background.
  EXPECT_EQ(m.at(gap + 4 * (w + gap) + w / 2, gap + (h + gap) + h / 2).r, 0.02f);
}

}  // namespace
}  // namespace pathlab::app
