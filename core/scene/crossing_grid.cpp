// Crossing counts through a 2D grid of projected triangles (crossing_grid.h).
#include "core/scene/crossing_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pathlab {

namespace {

// Moller-Trumbore, both faces, t > 0: whether the ray o + t d crosses triangle (a, b, c).
bool crosses(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, pv = glm::cross(d, e2);
  const float det = glm::dot(e1, pv);
  if (std::abs(det) < 1e-20f) return false;
  const float inv = 1.f / det;
  const Vec3 tv = o - a;
  const float u = glm::dot(tv, pv) * inv;
  if (u < 0.f || u > 1.f) return false;
  const Vec3 qv = glm::cross(tv, e1);
  const float v = glm::dot(d, qv) * inv;
  if (v < 0.f || u + v > 1.f) return false;
  return glm::dot(e2, qv) * inv > 0.f;
}

// About one triangle a cell, at most 1024 cells a side.
constexpr int kMaxCellsPerSide = 1024;

}  // namespace

Vec3 CrossingGrid::direction() { return glm::normalize(Vec3(0.5773f, 0.6213f, 0.5297f)); }

CrossingGrid::CrossingGrid(std::vector<Triangle> triangles) : triangles_(std::move(triangles)) {
  const Vec3 d = direction();
  u_ = glm::normalize(glm::cross(d, Vec3(1.f, 0.f, 0.f)));
  v_ = glm::cross(d, u_);
  if (triangles_.empty()) return;
  std::vector<Vec2> tlo(triangles_.size()), thi(triangles_.size());
  lo_ = Vec2(std::numeric_limits<float>::max());
  hi_ = Vec2(-std::numeric_limits<float>::max());
  for (size_t i = 0; i < triangles_.size(); ++i) {
    const Vec2 a = project(triangles_[i].a), b = project(triangles_[i].b), c = project(triangles_[i].c);
    tlo[i] = glm::min(a, glm::min(b, c));
    thi[i] = glm::max(a, glm::max(b, c));
    lo_ = glm::min(lo_, tlo[i]);
    hi_ = glm::max(hi_, thi[i]);
  }
  // Padded so that a point on a triangle's shadow edge, rounded differently, still finds it.
  const Vec2 pad = 1e-4f * (hi_ - lo_) + Vec2(1e-6f);
  lo_ -= pad;
  hi_ += pad;
  auto forCells = [&](size_t i, auto&& f) {
    const int x0 = cellX(tlo[i].x - pad.x), x1 = cellX(thi[i].x + pad.x);
    const int y0 = cellY(tlo[i].y - pad.y), y1 = cellY(thi[i].y + pad.y);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) f(size_t(y) * size_t(nx_) + size_t(x));
  };
  // A triangle goes into every cell its padded shadow box covers: coarser cells when long thin
  // triangles would fill too many (the entries stay O(triangles)).
  int side = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(triangles_.size())))), 1,
                        kMaxCellsPerSide);
  for (;; side /= 2) {
    nx_ = ny_ = side;
    inverseCell_ = Vec2(float(nx_), float(ny_)) / glm::max(hi_ - lo_, Vec2(1e-30f));
    if (side == 1) break;
    size_t entries = 0;
    for (size_t i = 0; i < triangles_.size(); ++i)
      entries += size_t(cellX(thi[i].x + pad.x) - cellX(tlo[i].x - pad.x) + 1) *
                 size_t(cellY(thi[i].y + pad.y) - cellY(tlo[i].y - pad.y) + 1);
    if (entries <= 16 * triangles_.size() + size_t(side) * size_t(side)) break;
  }
  // Counting sort of (cell, triangle).
  cellStart_.assign(size_t(nx_) * size_t(ny_) + 1, 0);
  for (size_t i = 0; i < triangles_.size(); ++i) forCells(i, [&](size_t c) { ++cellStart_[c + 1]; });
  for (size_t c = 1; c < cellStart_.size(); ++c) cellStart_[c] += cellStart_[c - 1];
  cellTriangles_.resize(cellStart_.back());
  std::vector<uint32_t> fill(cellStart_.begin(), cellStart_.end() - 1);
  for (size_t i = 0; i < triangles_.size(); ++i) forCells(i, [&](size_t c) { cellTriangles_[fill[c]++] = uint32_t(i); });
}

int CrossingGrid::cellX(float x) const { return std::clamp(static_cast<int>((x - lo_.x) * inverseCell_.x), 0, nx_ - 1); }
int CrossingGrid::cellY(float y) const { return std::clamp(static_cast<int>((y - lo_.y) * inverseCell_.y), 0, ny_ - 1); }

int CrossingGrid::crossings(const Vec3& p) const {
  if (triangles_.empty()) return 0;
  const Vec2 q = project(p);
  // The ray's shadow is the point q: no triangle outside the grid's box can be crossed.
  if (q.x < lo_.x || q.y < lo_.y || q.x > hi_.x || q.y > hi_.y) return 0;
  const size_t c = size_t(cellY(q.y)) * size_t(nx_) + size_t(cellX(q.x));
  const Vec3 d = direction();
  int n = 0;
  for (uint32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
    const Triangle& t = triangles_[cellTriangles_[k]];
    n += crosses(p, d, t.a, t.b, t.c) ? 1 : 0;
  }
  return n;
}

}  // namespace pathlab
