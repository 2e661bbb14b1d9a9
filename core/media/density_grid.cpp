// The majorant grid of a density grid.
#include "core/media/density_grid.h"

namespace pathlab {

MajorantGrid::MajorantGrid(const DensityGrid& grid) {
  if (grid.voxelCount() == 0) return;
  // The field is non-zero only within (origin - 1, origin + size) per axis (trilinear support):
  // the lattice starts one voxel below the first sample.
  lo_ = Vec3(grid.origin) - Vec3(1.f);
  const glm::ivec3 span = grid.size + glm::ivec3(1);
  cells_ = (span + glm::ivec3(kCellVoxels - 1)) / kCellVoxels;
  max_.assign(size_t(cells_.x) * size_t(cells_.y) * size_t(cells_.z), 0.f);
  // Cell c covers offsets [c K - 1, (c + 1) K - 1] from origin; the field there reads voxels
  // [c K - 1, (c + 1) K]. Each voxel raises every cell whose range holds it.
  for (int k = 0; k < grid.size.z; ++k)
    for (int j = 0; j < grid.size.y; ++j)
      for (int i = 0; i < grid.size.x; ++i) {
        const float v = grid.voxel(i, j, k);
        if (!(v > 0.f)) continue;
        const glm::ivec3 q(i, j, k);
        glm::ivec3 c0, c1;
        for (int a = 0; a < 3; ++a) {
          // cells c with c K - 1 <= q <= (c + 1) K: c from ceil(q / K) - 1 to floor((q + 1) / K)
          c0[a] = std::max(0, (q[a] + kCellVoxels - 1) / kCellVoxels - 1);
          c1[a] = std::min(cells_[a] - 1, (q[a] + 1) / kCellVoxels);
        }
        for (int z = c0.z; z <= c1.z; ++z)
          for (int y = c0.y; y <= c1.y; ++y)
            for (int x = c0.x; x <= c1.x; ++x) {
              float& m = max_[(size_t(z) * size_t(cells_.y) + size_t(y)) * size_t(cells_.x) + size_t(x)];
              m = std::max(m, v);
            }
      }
}

}  // namespace pathlab
