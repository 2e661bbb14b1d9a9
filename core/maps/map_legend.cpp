// Legend panels of the technique maps' PNGs.
#include "core/maps/map_legend.h"

#include "core/maps/map_colours.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <map>
#include <vector>

#include <stb/stb_easy_font.h>

namespace pathlab {

namespace {

constexpr int kPanelWidth = 190, kLine = 18, kMargin = 8, kSwatch = 12;
const Vec3 kPanelColour{0.12f, 0.12f, 0.12f}, kTextColour{0.95f, 0.95f, 0.95f};

// The map at the top-left of a canvas widened by the panel and as tall as the larger of the two.
Image canvas(const Image& map, int panelHeight) {
  Image c{map.width + kPanelWidth, std::max(map.height, panelHeight), {}};
  c.rgb.assign(3 * static_cast<size_t>(c.width) * static_cast<size_t>(c.height), 0.f);
  fillRect(c, 0, 0, c.width, c.height, kPanelColour);
  for (int y = 0; y < map.height; ++y)
    std::copy_n(map.rgb.begin() + 3 * static_cast<std::ptrdiff_t>(y) * map.width, 3 * map.width,
                c.rgb.begin() + 3 * static_cast<std::ptrdiff_t>(y) * c.width);
  return c;
}

void swatch(Image& img, int x, int y, const Vec3& colour) {
  fillRect(img, x, y, kSwatch, kSwatch, Vec3(0.5f));
  fillRect(img, x + 1, y + 1, kSwatch - 2, kSwatch - 2, colour);
}

// A technique's swatch as the map draws it (a merge's striped, in the map's own rows).
void techniqueSwatch(Image& img, int x, int y, Technique t) {
  fillRect(img, x, y, kSwatch, kSwatch, Vec3(0.5f));
  for (int dy = 1; dy < kSwatch - 1; ++dy) fillRect(img, x + 1, y + dy, kSwatch - 2, 1, techniqueColourAt(t, 0, dy));
}

}  // namespace

void fillRect(Image& img, int x0, int y0, int w, int h, const Vec3& colour) {
  for (int y = std::max(y0, 0); y < std::min(y0 + h, img.height); ++y)
    for (int x = std::max(x0, 0); x < std::min(x0 + w, img.width); ++x) {
      const size_t i = 3 * (static_cast<size_t>(y) * static_cast<size_t>(img.width) + static_cast<size_t>(x));
      img.rgb[i] = colour.r;
      img.rgb[i + 1] = colour.g;
      img.rgb[i + 2] = colour.b;
    }
}

int drawText(Image& img, int x, int y, const std::string& text, const Vec3& colour, int scale) {
  // stb_easy_font builds each glyph from axis-aligned quads of 4 vertices (x, y, z, rgba8).
  struct Vertex {
    float x, y, z;
    unsigned char rgba[4];
  };
  std::vector<Vertex> quads(4 * 64 * std::max<size_t>(text.size(), 1));
  std::string copy = text;
  const int n = stb_easy_font_print(0.f, 0.f, copy.data(), nullptr, quads.data(),
                                    static_cast<int>(quads.size() * sizeof(Vertex)));
  for (int q = 0; q < n; ++q) {
    const Vertex& a = quads[4 * static_cast<size_t>(q)];
    const Vertex& c = quads[4 * static_cast<size_t>(q) + 2];
    fillRect(img, x + static_cast<int>(a.x) * scale, y + static_cast<int>(a.y) * scale,
             static_cast<int>(c.x - a.x) * scale, static_cast<int>(c.y - a.y) * scale, colour);
  }
  return stb_easy_font_width(copy.data()) * scale;
}

Image withDominantLegend(const Image& map, const DominantMap& m, const std::string& title) {
  std::map<int, size_t> wins;  // by technique index (ties and empty below zero)
  size_t lit = 0;
  for (const int x : m.technique) {
    ++wins[x];
    if (x != kDominantEmpty) ++lit;
  }
  const int entries = static_cast<int>(wins.size());
  Image img = canvas(map, kMargin + (entries + 2) * kLine);
  int y = kMargin;
  const int x0 = map.width + kMargin;
  drawText(img, x0, y, title, kTextColour);
  y += kLine + 4;
  auto percent = [&](size_t count) { return lit ? 100.0 * static_cast<double>(count) / static_cast<double>(lit) : 0.0; };
  for (const auto& [index, count] : wins) {
    if (index < 0) continue;
    const Technique x = Technique::fromIndex(static_cast<size_t>(index));
    techniqueSwatch(img, x0, y, x);
    drawText(img, x0 + kSwatch + 6, y, fmt::format("{} {:.0f}%", techniqueLabel(x), percent(count)), kTextColour);
    y += kLine;
  }
  swatch(img, x0, y, kTieColour);
  drawText(img, x0 + kSwatch + 6, y, fmt::format("tie {:.0f}%", percent(wins.count(kDominantTie) ? wins[kDominantTie] : 0)),
           kTextColour);
  y += kLine;
  swatch(img, x0, y, kEmptyColour);
  drawText(img, x0 + kSwatch + 6, y, "no light", kTextColour);
  return img;
}

Image withShareBar(const Image& map, const std::string& title, bool hatchKey) {
  constexpr int kBarHeight = 160, kBarWidth = 20;
  Image img = canvas(map, kMargin + kLine + kBarHeight + (hatchKey ? 4 * kLine : kLine) + kMargin);
  const int x0 = map.width + kMargin;
  int y = kMargin;
  drawText(img, x0, y, title, kTextColour);
  y += kLine + 4;
  for (int i = 0; i < kBarHeight; ++i)
    fillRect(img, x0, y + i, kBarWidth, 1, viridis(1.f - static_cast<float>(i) / static_cast<float>(kBarHeight - 1)));
  drawText(img, x0 + kBarWidth + 6, y, "1", kTextColour);
  drawText(img, x0 + kBarWidth + 6, y + kBarHeight / 2 - 6, "0.5", kTextColour);
  drawText(img, x0 + kBarWidth + 6, y + kBarHeight - 12, "0 share", kTextColour);
  y += kBarHeight + 8;
  if (!hatchKey) return img;
  for (int dy = 0; dy < kSwatch; ++dy)
    for (int dx = 0; dx < kSwatch; ++dx) fillRect(img, x0 + dx, y + dy, 1, 1, onHatch(dx, dy) ? kHatchColour : viridis(0.f));
  drawText(img, x0 + kSwatch + 6, y, "cannot sample", kTextColour);
  y += kLine;
  swatch(img, x0, y, viridis(0.f));
  drawText(img, x0 + kSwatch + 6, y, "weighted away", kTextColour);
  y += kLine;
  swatch(img, x0, y, kEmptyColour);
  drawText(img, x0 + kSwatch + 6, y, "no light", kTextColour);
  return img;
}

}  // namespace pathlab
