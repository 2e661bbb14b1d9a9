// The regions variance-aware MIS estimates its factors over (core/bpt/variance_aware_mis.h):
// cells of kVarianceAwareCell pixels a side cut along the pass's work items (pass_tiles.h), so that
// all of a region's camera samples are rendered by the one thread that renders its item, in the
// item's order. The cells double while the factors' tables would take more than kVarianceAwareBytes.
#pragma once

#include "core/render/pass_tiles.h"

#include <cstdint>
#include <vector>

namespace pathlab {

struct VarianceAwareRegions {
  int cell = 0;  // pixels a side
  int count = 0;
  std::vector<int32_t> regionOfPixel;  // row-major
};

// The cells of `cell` pixels a side cut along `tiles`, each tile's row by row.
VarianceAwareRegions varianceAwareRegions(int width, int height, const std::vector<PassTile>& tiles, int cell);
// The cell size the factors use for this image and length: kVarianceAwareCell, doubled while
// VarianceAwareFactors::bytesFor would pass kVarianceAwareBytes.
int varianceAwareCell(int width, int height, int maxLength);
// The bytes of the factors' tables for this image and length (RenderSession's work items).
uint64_t varianceAwareBytes(int width, int height, int maxLength);
// The same for optimal MIS's sums (core/bpt/optimal_mis.h): kOptimalMisCell doubled while
// OptimalMis::bytesFor would pass kOptimalMisBytes, and the bytes at that cell.
int optimalMisCell(int width, int height, int maxLength);
uint64_t optimalMisBytes(int width, int height, int maxLength);

}  // namespace pathlab
