// Legends and colour bars drawn into the technique maps' PNGs (the viewer draws its own in ImGui):
// text from stb_easy_font's quads, filled rectangles, a panel to the right of the map.
#pragma once

#include "core/film/film.h"
#include "core/maps/technique_maps.h"

#include <string>

namespace pathlab {

// Display colours (as map_colours.h) drawn in place; clipped to the image.
void fillRect(Image& img, int x0, int y0, int w, int h, const Vec3& colour);
// Text with its top-left corner at (x, y), each font pixel scale x scale; returns its width.
int drawText(Image& img, int x, int y, const std::string& text, const Vec3& colour, int scale = 2);

// The map with a legend panel to its right: a swatch and "(s,t) NN%" or "M(s,t) NN%" (its share of the lit
// pixels) for every technique that wins somewhere, then ties and pixels without light.
Image withDominantLegend(const Image& map, const DominantMap& m, const std::string& title);
// The map with a vertical viridis colour bar from 0 to 1 to its right; with `hatchKey` also the
// keys of the cannot-sample map (hatched: cannot sample; dark: weighted away; black: no light).
Image withShareBar(const Image& map, const std::string& title, bool hatchKey);

}  // namespace pathlab
