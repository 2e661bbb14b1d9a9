// OpenVDB files (Debian's libopenvdb-dev), read and written in this one translation unit: a float
// density grid becomes a DensityGrid (its active region, densified) and the grid's own
// index-to-world transform; and a DensityGrid is written back as a .vdb (pathlab make-volume).
#pragma once

#include "core/media/density_grid.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab {

// "FILE: problem" as what(): a missing or corrupt file, a missing grid, an unsupported grid type
// or transform, NaN, negative or huge densities, a grid too large to densify.
class VdbError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The most voxels a density grid may span (its active bounding box): 256 MiB of floats.
inline constexpr size_t kMaxDensityVoxels = size_t(1) << 26;
// Densities above this are refused: an optical depth of 1e6 per unit of sigma_t is a unit error.
inline constexpr float kMaxDensityValue = 1e6f;

struct VdbDensity {
  DensityGrid grid;
  Mat4 indexToWorld{1.f};  // the grid's own (affine) transform, index space to the file's space
};

// The float (or double) grid named `gridName` of the .vdb at `path` (read through
// core/io/guarded_file.h), multiplied by `scale`.
VdbDensity readDensityVdb(const std::string& path, const std::string& gridName, float scale = 1.f);

// Writes `grid` as the float grid `gridName` with voxel size `voxelSize` and voxel (0, 0, 0) of the
// index space at world point `origin`, written to a temporary file beside `path` and renamed over
// it. Voxels of value 0 are left inactive (the background).
void writeDensityVdb(const std::string& path, const std::string& gridName, const DensityGrid& grid, float voxelSize,
                     const Vec3& origin);

}  // namespace pathlab
