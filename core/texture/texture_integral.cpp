// The mean of a filtered texture over a uv triangle by clipping against the texel grid and
// integrating each piece in closed form (see texture_integral.h).
#include "core/texture/texture_integral.h"

#include "core/math/rng.h"
#include "core/sampling/warp.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace pathlab {
namespace {

struct Point {
  double x, y;
};

// A convex polygon: a triangle clipped by at most four axis-aligned lines has at most 7 vertices.
struct Polygon {
  Point v[8];
  int n = 0;
};

// Sutherland-Hodgman against the half-plane sign * (coordinate - c) >= 0 (y if `alongY`).
Polygon clip(const Polygon& in, bool alongY, double c, double sign) {
  Polygon out;
  for (int i = 0; i < in.n; ++i) {
    const Point& a = in.v[i];
    const Point& b = in.v[(i + 1) % in.n];
    const double da = sign * ((alongY ? a.y : a.x) - c);
    const double db = sign * ((alongY ? b.y : b.x) - c);
    if (da >= 0.0) out.v[out.n++] = a;
    if ((da >= 0.0) != (db >= 0.0)) {
      const double t = da / (da - db);
      Point p{a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)};
      (alongY ? p.y : p.x) = c;  // exactly on the line, whatever the rounding of t
      out.v[out.n++] = p;
    }
  }
  return out;
}

// Integrals of 1, x, y and xy over a counter-clockwise polygon, in coordinates relative to
// (ox, oy): Green's theorem turns each into a sum over the edges (Steger 1996, "On the
// calculation of arbitrary moments of polygons", eqs. for m00, m10, m01, m11).
struct Moments {
  double a = 0.0, x = 0.0, y = 0.0, xy = 0.0;
};

Moments moments(const Polygon& p, double ox, double oy) {
  Moments m;
  for (int i = 0; i < p.n; ++i) {
    const Point& q = p.v[(i + 1) % p.n];
    const double x0 = p.v[i].x - ox, y0 = p.v[i].y - oy, x1 = q.x - ox, y1 = q.y - oy;
    const double c = x0 * y1 - x1 * y0;
    m.a += c;
    m.x += (x0 + x1) * c;
    m.y += (y0 + y1) * c;
    m.xy += (x0 * y1 + 2.0 * x0 * y0 + 2.0 * x1 * y1 + x1 * y0) * c;
  }
  m.a /= 2.0;
  m.x /= 6.0;
  m.y /= 6.0;
  m.xy /= 24.0;
  return m;
}

// Jittered k x k stratified quadrature of sample() over the triangle (an area-preserving warp of
// the square, so the strata have equal areas), for footprints the exact method should not walk.
// Jittered, not on a regular grid: a grid coarser than the texels would alias with them.
Vec4 quadrature(const Texture& texture, const Vec2 uv[3], int k) {
  Pcg32 rng(0x7e57u, uint64_t(k));  // fixed: the same triangle always gets the same power
  glm::dvec4 sum(0.0);
  for (int a = 0; a < k; ++a) {
    for (int b = 0; b < k; ++b) {
      const Vec2 jitter = rng.next2D();
      const Vec2 bary = sampleUniformTriangle(
          Vec2(std::min((float(a) + jitter.x) / float(k), kOneMinusEpsilon),
               std::min((float(b) + jitter.y) / float(k), kOneMinusEpsilon)));
      const Vec2 uvAt = bary.x * uv[0] + bary.y * uv[1] + (1.f - bary.x - bary.y) * uv[2];
      sum += glm::dvec4(texture.sampleImage(uvAt));
    }
  }
  return Vec4(sum / double(k * k));
}

// Beyond these the exact method's cost (cells and rows walked) is not worth it: the triangle
// covers the texture many times over, and 512^2 stratified samples average it well.
constexpr double kMaxCoveredCopies = 16.0;
constexpr double kMaxRowsAndColumns = double(1 << 22);
constexpr int kLargeFootprintSamples = 512;
// A triangle with less area than this (in cells) has no usable orientation in double.
constexpr double kMinArea = 1e-9;
// Coordinates beyond this lose whole cells to rounding (and would overflow the cell indices).
constexpr double kMaxCoordinate = 1e15;

}  // namespace

Vec4 meanOverTriangle(const Texture& texture, Vec2 uv0, Vec2 uv1, Vec2 uv2) {
  // The transform is affine: it maps the uv triangle onto the image-space triangle with uniform
  // area measure, so the mean over the one is the mean over the other.
  const Vec2 uv[3] = {texture.transform.apply(uv0), texture.transform.apply(uv1),
                      texture.transform.apply(uv2)};
  if (!texture.valid()) return Vec4(0.f);
  const double w = texture.width, h = texture.height;
  // Cell space: bilinear filtering is one polynomial between four texel centres (at half-integer
  // texel coordinates), nearest filtering is constant on each texel.
  const double shift = texture.nearest ? 0.0 : 0.5;
  Point p[3];
  double minX = INFINITY, minY = INFINITY, maxX = -INFINITY, maxY = -INFINITY;
  double maxEdge = 0.0;
  for (int k = 0; k < 3; ++k) {
    p[k] = {double(uv[k].x) * w - shift, double(uv[k].y) * h - shift};
    if (!(std::abs(p[k].x) < kMaxCoordinate && std::abs(p[k].y) < kMaxCoordinate)) {
      return texture.sampleImage(uv[0]);  // non-finite or astronomically far: sample() reduces it
    }
    minX = std::min(minX, p[k].x);
    minY = std::min(minY, p[k].y);
    maxX = std::max(maxX, p[k].x);
    maxY = std::max(maxY, p[k].y);
  }
  // Coordinates relative to the first covered cell keep the arithmetic small; texel indices are
  // origin + cell, wrapped by Texture::fetch, so whole periods need no special handling.
  const auto originX = int64_t(std::floor(minX)), originY = int64_t(std::floor(minY));
  for (Point& q : p) {
    q.x -= double(originX);
    q.y -= double(originY);
  }
  for (int k = 0; k < 3; ++k) {
    maxEdge = std::max(maxEdge, std::hypot(p[(k + 1) % 3].x - p[k].x, p[(k + 1) % 3].y - p[k].y));
  }
  double area = 0.5 * ((p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y));
  if (area < 0.0) {
    std::swap(p[1], p[2]);
    area = -area;
  }
  if (!(area > kMinArea)) {
    // Collinear uvs: the barycentric strata weight the segment as the triangle does. Coincident
    // uvs (a mesh without texture coordinates) need one lookup.
    if (maxEdge == 0.0) return texture.sampleImage(uv[0]);
    return quadrature(texture, uv, std::clamp(int(std::ceil(16.0 * maxEdge)), 16, 256));
  }
  const double rows = std::ceil(maxY - double(originY)), columns = std::ceil(maxX - double(originX));
  if (area > kMaxCoveredCopies * std::max(w * h, 4096.0) || rows + columns > kMaxRowsAndColumns) {
    return quadrature(texture, uv, kLargeFootprintSamples);
  }

  // Edge functions of the counter-clockwise triangle: a cell whose four corners are inside is
  // covered whole, and its integral is the mean of its corners without clipping.
  auto inside = [&](double x, double y) {
    for (int k = 0; k < 3; ++k) {
      const Point& a = p[k];
      const Point& b = p[(k + 1) % 3];
      if ((b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x) < 0.0) return false;
    }
    return true;
  };
  auto corners = [&](int64_t i, int64_t j, Vec4 c[4]) {
    const int64_t x = originX + i, y = originY + j;
    c[0] = texture.fetch(x, y);
    if (texture.nearest) {
      c[1] = c[2] = c[3] = c[0];
    } else {
      c[1] = texture.fetch(x + 1, y);
      c[2] = texture.fetch(x, y + 1);
      c[3] = texture.fetch(x + 1, y + 1);
    }
  };

  Polygon triangle;
  triangle.n = 3;
  std::copy(p, p + 3, triangle.v);
  glm::dvec4 integral(0.0);
  double coveredArea = 0.0;
  for (int64_t j = 0; double(j) < rows; ++j) {
    const Polygon strip = clip(clip(triangle, true, double(j), 1.0), true, double(j + 1), -1.0);
    if (strip.n < 3) continue;
    double stripMin = INFINITY, stripMax = -INFINITY;
    for (int k = 0; k < strip.n; ++k) {
      stripMin = std::min(stripMin, strip.v[k].x);
      stripMax = std::max(stripMax, strip.v[k].x);
    }
    for (auto i = int64_t(std::floor(stripMin)); double(i) < stripMax; ++i) {
      const double x0 = double(i), y0 = double(j);
      Vec4 c[4];
      if (inside(x0, y0) && inside(x0 + 1.0, y0) && inside(x0, y0 + 1.0) && inside(x0 + 1.0, y0 + 1.0)) {
        corners(i, j, c);
        integral += 0.25 * (glm::dvec4(c[0]) + glm::dvec4(c[1]) + glm::dvec4(c[2]) + glm::dvec4(c[3]));
        coveredArea += 1.0;
        continue;
      }
      const Polygon piece = clip(clip(strip, false, x0, 1.0), false, x0 + 1.0, -1.0);
      if (piece.n < 3) continue;
      const Moments m = moments(piece, x0, y0);
      if (!(m.a > 0.0)) continue;
      corners(i, j, c);
      // Bilinear in cell coordinates: c00 + (c10 - c00) x + (c01 - c00) y + (c00 - c10 - c01 + c11) xy.
      const glm::dvec4 c00(c[0]), c10(c[1]), c01(c[2]), c11(c[3]);
      integral += c00 * m.a + (c10 - c00) * m.x + (c01 - c00) * m.y + (c00 - c10 - c01 + c11) * m.xy;
      coveredArea += m.a;
    }
  }
  if (!(coveredArea > 0.0)) return texture.sampleImage(uv[0]);
  // The pieces partition the triangle: dividing by the sum of their areas, not by the triangle's,
  // keeps the rounding of the clipping out of the mean (a constant texture gives that constant).
  return Vec4(integral / coveredArea);
}

}  // namespace pathlab
