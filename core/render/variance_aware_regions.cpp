// The regions of variance-aware MIS: cells cut along the work items (variance_aware_regions.h).
#include "core/render/variance_aware_regions.h"

#include "core/bpt/optimal_mis.h"
#include "core/bpt/variance_aware_mis.h"

#include <algorithm>

namespace pathlab {

namespace {

// How many regions the cells of `cell` pixels make over `tiles`: each tile's cells.
uint64_t countRegions(const std::vector<PassTile>& tiles, int cell) {
  uint64_t n = 0;
  for (const PassTile& t : tiles) {
    if (t.pixels() <= 0) continue;
    const uint64_t columns = static_cast<uint64_t>((t.x1 - 1) / cell - t.x0 / cell + 1);
    const uint64_t rows = static_cast<uint64_t>((t.y1 - 1) / cell - t.y0 / cell + 1);
    n += columns * rows;
  }
  return n;
}

using TableBytes = uint64_t (*)(int width, int height, uint64_t regions, int maxLength);

uint64_t bytesAt(int width, int height, int maxLength, const std::vector<PassTile>& tiles, int cell,
                 TableBytes bytesFor = &VarianceAwareFactors::bytesFor) {
  return bytesFor(width, height, countRegions(tiles, cell), maxLength);
}

}  // namespace

VarianceAwareRegions varianceAwareRegions(int width, int height, const std::vector<PassTile>& tiles, int cell) {
  VarianceAwareRegions r;
  r.cell = cell;
  r.regionOfPixel.assign(static_cast<size_t>(width) * static_cast<size_t>(height), -1);
  for (const PassTile& t : tiles) {
    if (t.pixels() <= 0) continue;
    const int cx0 = t.x0 / cell, cx1 = (t.x1 - 1) / cell, cy0 = t.y0 / cell, cy1 = (t.y1 - 1) / cell;
    const int columns = cx1 - cx0 + 1;
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x)
        r.regionOfPixel[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)] =
            r.count + (y / cell - cy0) * columns + (x / cell - cx0);
    r.count += columns * (cy1 - cy0 + 1);
  }
  return r;
}

int varianceAwareCell(int width, int height, int maxLength) {
  const std::vector<PassTile> tiles = passTiles(width, height);
  int cell = kVarianceAwareCell;
  while (cell < std::max(width, height) && bytesAt(width, height, maxLength, tiles, cell) > kVarianceAwareBytes)
    cell *= 2;
  return cell;
}

uint64_t varianceAwareBytes(int width, int height, int maxLength) {
  return bytesAt(width, height, maxLength, passTiles(width, height), varianceAwareCell(width, height, maxLength));
}

int optimalMisCell(int width, int height, int maxLength) {
  const std::vector<PassTile> tiles = passTiles(width, height);
  int cell = kOptimalMisCell;
  while (cell < std::max(width, height) &&
         bytesAt(width, height, maxLength, tiles, cell, &OptimalMis::bytesFor) > kOptimalMisBytes)
    cell *= 2;
  return cell;
}

uint64_t optimalMisBytes(int width, int height, int maxLength) {
  return bytesAt(width, height, maxLength, passTiles(width, height), optimalMisCell(width, height, maxLength),
                 &OptimalMis::bytesFor);
}

}  // namespace pathlab
