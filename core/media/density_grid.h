// A density field on a regular voxel lattice: an OpenVDB float grid's active region, densified
// (core/io/vdb_file.h reads one), and the coarse majorant grid that bounds it for delta and ratio
// tracking (issue 35; pbrt-v4's MajorantGrid and DDAMajorantIterator, Novák et al. 2018 sec. 4).
#pragma once

#include "core/math/types.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pathlab {

// Voxel values in index space, OpenVDB's convention: voxel (i, j, k) is a sample at the integer
// point (i, j, k), and the field between samples is their trilinear interpolation (openvdb's
// BoxSampler). Outside the stored block the field is zero (the grid's background).
struct DensityGrid {
  glm::ivec3 origin{0};          // index of the first stored voxel
  glm::ivec3 size{0};            // stored voxels per axis
  std::vector<float> values;     // x fastest, then y, then z; finite and >= 0

  size_t voxelCount() const { return static_cast<size_t>(size.x) * size_t(size.y) * size_t(size.z); }
  // The voxel at offset (i, j, k) from origin; zero outside.
  float voxel(int i, int j, int k) const {
    if (i < 0 || j < 0 || k < 0 || i >= size.x || j >= size.y || k >= size.z) return 0.f;
    return values[(size_t(k) * size_t(size.y) + size_t(j)) * size_t(size.x) + size_t(i)];
  }
  // The trilinear field at index-space point p.
  float lookup(const Vec3& p) const {
    const Vec3 q = p - Vec3(origin);
    const Vec3 f = glm::floor(q);
    if (!(f.x >= -1.f && f.y >= -1.f && f.z >= -1.f && f.x < float(size.x) && f.y < float(size.y) && f.z < float(size.z)))
      return 0.f;  // also NaN
    const int i = int(f.x), j = int(f.y), k = int(f.z);
    const Vec3 w = q - f;
    auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
    const float x00 = lerp(voxel(i, j, k), voxel(i + 1, j, k), w.x);
    const float x10 = lerp(voxel(i, j + 1, k), voxel(i + 1, j + 1, k), w.x);
    const float x01 = lerp(voxel(i, j, k + 1), voxel(i + 1, j, k + 1), w.x);
    const float x11 = lerp(voxel(i, j + 1, k + 1), voxel(i + 1, j + 1, k + 1), w.x);
    return lerp(lerp(x00, x10, w.y), lerp(x01, x11, w.y), w.z);
  }
  float maxValue() const { return values.empty() ? 0.f : *std::max_element(values.begin(), values.end()); }
};

// The largest density in each cell of a coarse lattice over the grid (cells of kCellVoxels voxels
// a side), including every voxel the trilinear field inside the cell reads: a majorant of the
// field, cell by cell. Tracking walks its cells along the ray (a 3D DDA, Amanatides and Woo 1987)
// with the cell's majorant, so empty space and thin regions cost few tentative collisions.
class MajorantGrid {
 public:
  static constexpr int kCellVoxels = 8;

  MajorantGrid() = default;
  explicit MajorantGrid(const DensityGrid& grid);

  glm::ivec3 cells() const { return cells_; }
  float cellMajorant(int i, int j, int k) const {
    return max_[(size_t(k) * size_t(cells_.y) + size_t(j)) * size_t(cells_.x) + size_t(i)];
  }

  // Calls visit(t0, t1, majorant) for each cell the ray o + t d (index space; t in the caller's
  // units) crosses within [tMin, tMax], in order, until visit returns false. Nothing outside the
  // lattice (where the field is zero) is visited.
  template <class Visit>
  void traverse(const Vec3& o, const Vec3& d, float tMin, float tMax, Visit&& visit) const;

 private:
  Vec3 lo_{0.f};            // index-space corner of cell (0, 0, 0)
  glm::ivec3 cells_{0};
  std::vector<float> max_;
};

template <class Visit>
void MajorantGrid::traverse(const Vec3& o, const Vec3& d, float tMin, float tMax, Visit&& visit) const {
  if (max_.empty()) return;
  // Cell coordinates: c(t) = oc + t dc.
  const float inv = 1.f / float(kCellVoxels);
  const Vec3 oc = (o - lo_) * inv, dc = d * inv;
  float t0 = tMin, t1 = tMax;
  for (int a = 0; a < 3; ++a) {
    if (dc[a] == 0.f) {
      if (!(oc[a] >= 0.f && oc[a] < float(cells_[a]))) return;
      continue;
    }
    float ta = -oc[a] / dc[a], tb = (float(cells_[a]) - oc[a]) / dc[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 < t1)) return;
  glm::ivec3 cell, step;
  Vec3 tNext, tDelta;
  const Vec3 p = oc + t0 * dc;
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(int(std::floor(p[a])), 0, cells_[a] - 1);
    if (dc[a] > 0.f) {
      step[a] = 1;
      tNext[a] = t0 + (float(cell[a] + 1) - p[a]) / dc[a];
      tDelta[a] = 1.f / dc[a];
    } else if (dc[a] < 0.f) {
      step[a] = -1;
      tNext[a] = t0 + (float(cell[a]) - p[a]) / dc[a];
      tDelta[a] = -1.f / dc[a];
    } else {
      step[a] = 0;
      tNext[a] = tDelta[a] = std::numeric_limits<float>::infinity();
    }
  }
  // Each step leaves one cell; a ray crosses at most the sum of the cell counts (and the guard
  // keeps a float that stops advancing from looping).
  const int maxSteps = cells_.x + cells_.y + cells_.z + 3;
  for (int s = 0; s < maxSteps; ++s) {
    const int a = tNext.x <= tNext.y ? (tNext.x <= tNext.z ? 0 : 2) : (tNext.y <= tNext.z ? 1 : 2);
    const float tEnd = std::min(tNext[a], t1);
    if (tEnd > t0 && !visit(t0, tEnd, cellMajorant(cell.x, cell.y, cell.z))) return;
    if (tEnd >= t1) return;
    t0 = tEnd;
    cell[a] += step[a];
    if (cell[a] < 0 || cell[a] >= cells_[a]) return;
    tNext[a] += tDelta[a];
  }
}

}  // namespace pathlab
