// passTiles: the bisection of the film into a pass's work items, in their fixed order.
#include "core/render/pass_tiles.h"

#include <algorithm>

namespace pathlab {

namespace {

// TBB's blocked_range2d: halve the rows unless the columns are longer; a side of 16 or fewer
// pixels (its grain size) is never halved. Seven levels: the auto_partitioner's depth on two cores.
constexpr int kGrain = 16;
constexpr int kDepth = 7;

void bisect(PassTile tile, int depth, std::vector<PassTile>& leaves) {
  const int rows = tile.y1 - tile.y0, cols = tile.x1 - tile.x0;
  if (depth == 0 || (rows <= kGrain && cols <= kGrain)) {
    leaves.push_back(tile);
    return;
  }
  PassTile first = tile, second = tile;
  if (rows < cols) {
    first.x1 = second.x0 = tile.x0 + cols / 2;
  } else {
    first.y1 = second.y0 = tile.y0 + rows / 2;
  }
  bisect(first, depth - 1, leaves);
  bisect(second, depth - 1, leaves);
}

}  // namespace

std::vector<PassTile> passTiles(int width, int height, int maxPixels) {
  std::vector<PassTile> leaves, tiles;
  if (width <= 0 || height <= 0) return tiles;
  bisect(PassTile{0, 0, width, height}, kDepth, leaves);
  for (const PassTile& leaf : leaves) {
    const int rowsPerBand = std::max(1, maxPixels / (leaf.x1 - leaf.x0));
    for (int y = leaf.y0; y < leaf.y1; y += rowsPerBand)
      tiles.push_back(PassTile{leaf.x0, y, leaf.x1, std::min(leaf.y1, y + rowsPerBand)});
  }
  return tiles;
}

}  // namespace pathlab
