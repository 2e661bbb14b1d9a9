// The work items of a pass and the fixed order in which their splats are summed, whatever thread
// renders which (RenderSession::renderPass): the same seed then gives the same image bit for bit
// at any thread count.
//
// The order is the image bisected recursively, seven times at most: the longer side halved (the
// rows on a tie), the first half before the second, no side halved below 16 pixels; each leaf is
// visited row by row. It is the order in which TBB's auto_partitioner visited a
// blocked_range2d(0, height, 16, 0, width, 16) on one thread of a two-core machine (checked on
// 9,124 sizes, oneTBB 2021.8), where the images of the earlier sessions were rendered: those
// one-thread images stay bit for bit the same. (TBB's own order depends on the core count, so
// they were never the same across machines; now they are.)
#pragma once

#include <vector>

namespace pathlab {

// Rows [y0, y1) and columns [x0, x1) of the film, visited row by row.
struct PassTile {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  int pixels() const { return (x1 - x0) * (y1 - y0); }
  bool operator==(const PassTile&) const = default;
};

// The leaves of the bisection above, in order, each cut into bands of whole rows of at most
// maxPixels pixels (one row when a row is longer): smaller work items, the same visiting order.
std::vector<PassTile> passTiles(int width, int height, int maxPixels = 1024);

}  // namespace pathlab
