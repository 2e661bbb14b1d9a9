// meanOverTriangle: the mean of a filtered texture over a uv triangle, against closed forms and
// against a dense stratified quadrature of Texture::sample (wrap modes, uvs outside [0, 1],
// triangles smaller than a texel, collinear uvs, footprints covering the texture many times).
#include "core/math/rng.h"
#include "core/sampling/warp.h"
#include "core/texture/texture_integral.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

Texture floatTexture(int w, int h, std::vector<Vec4> texels, WrapMode wrap, bool nearest) {
  Texture t;
  t.width = w;
  t.height = h;
  t.texels = std::move(texels);
  t.wrapS = t.wrapT = wrap;
  t.nearest = nearest;
  return t;
}

// Half black, half bright along u: two texels, clamped, bilinear. The filtered value is 0 for
// u <= 1/4, ramps linearly to `bright` at u = 3/4 and stays there.
const Vec4 kBright(2.f, 1.f, 0.5f, 1.f);
Texture halfBlack() { return floatTexture(2, 1, {Vec4(0.f, 0.f, 0.f, 1.f), kBright}, WrapMode::ClampToEdge, false); }

// k x k stratified samples of sample() over the triangle (an area-preserving warp of the square).
glm::dvec4 quadrature(const Texture& t, Vec2 a, Vec2 b, Vec2 c, int k) {
  glm::dvec4 sum(0.0);
  for (int i = 0; i < k; ++i) {
    for (int j = 0; j < k; ++j) {
      const Vec2 bary = sampleUniformTriangle(Vec2((float(i) + 0.5f) / float(k), (float(j) + 0.5f) / float(k)));
      sum += glm::dvec4(t.sample(bary.x * a + bary.y * b + (1.f - bary.x - bary.y) * c));
    }
  }
  return sum / double(k * k);
}

void expectNear(const Vec4& a, const glm::dvec4& b, double tolerance, const std::string& what) {
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(double(a[c]), b[c], tolerance) << what << " channel " << c;
}

TEST(TextureIntegral, TrianglesOverTheBlackOrTheBrightHalf) {
  const Texture t = halfBlack();
  // Entirely where the filtered texture is black (u <= 1/4), also beyond the clamped edge.
  EXPECT_EQ(meanOverTriangle(t, {0.f, 0.f}, {0.25f, 0.f}, {0.1f, 1.f}), Vec4(0.f, 0.f, 0.f, 1.f));
  EXPECT_EQ(meanOverTriangle(t, {-3.f, 0.2f}, {0.2f, -5.f}, {0.f, 4.f}), Vec4(0.f, 0.f, 0.f, 1.f));
  // Entirely where it is bright (u >= 3/4).
  expectNear(meanOverTriangle(t, {0.75f, 0.f}, {1.f, 0.f}, {0.8f, 1.f}), glm::dvec4(kBright), 1e-7, "bright");
  expectNear(meanOverTriangle(t, {0.75f, 0.f}, {9.f, 0.3f}, {1.f, 7.f}), glm::dvec4(kBright), 1e-7, "beyond");
}

// The unit uv square split along its diagonal. With g(u) the ramp above, the triangle below the
// diagonal (v <= u) has mean 2 int g(u) u du = 35/48 of bright, the other 2 int g(u) (1 - u) du
// = 13/48 (their average is the texture's mean 1/2).
TEST(TextureIntegral, QuadOverTheHalfBlackTextureClosedForm) {
  const Texture t = halfBlack();
  const Vec4 lower = meanOverTriangle(t, {0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f});
  const Vec4 upper = meanOverTriangle(t, {0.f, 0.f}, {1.f, 1.f}, {0.f, 1.f});
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(lower[c], 35.0 / 48.0 * kBright[c], 1e-6) << c;
    EXPECT_NEAR(upper[c], 13.0 / 48.0 * kBright[c], 1e-6) << c;
  }
  // Orientation does not matter.
  EXPECT_NEAR(meanOverTriangle(t, {0.f, 0.f}, {1.f, 1.f}, {1.f, 0.f}).r, lower.r, 1e-6f);
}

// NEAREST 2 x 2 checker a b / c d (row 0 at v < 1/2): the triangle v <= u covers half of a, all
// of b and half of d, so its mean is a/4 + b/2 + d/4; the other a/4 + c/2 + d/4.
TEST(TextureIntegral, NearestCheckerQuadClosedForm) {
  const Vec4 a(1.f), b(0.f), c(8.f), d(4.f);
  const Texture t = floatTexture(2, 2, {a, b, c, d}, WrapMode::Repeat, true);
  const Vec4 lower = meanOverTriangle(t, {0.f, 0.f}, {1.f, 0.f}, {1.f, 1.f});
  const Vec4 upper = meanOverTriangle(t, {0.f, 0.f}, {1.f, 1.f}, {0.f, 1.f});
  EXPECT_NEAR(lower.r, 0.25f * a.r + 0.5f * b.r + 0.25f * d.r, 1e-6f);
  EXPECT_NEAR(upper.r, 0.25f * a.r + 0.5f * c.r + 0.25f * d.r, 1e-6f);
  // Shifted by whole periods of REPEAT: the same.
  EXPECT_NEAR(meanOverTriangle(t, {-3.f, 5.f}, {-2.f, 5.f}, {-2.f, 6.f}).r, lower.r, 1e-6f);
}

// Random textures, every wrap mode and filter, triangles of every size around and outside
// [0, 1]^2, against 800^2 stratified samples. The difference is the quadrature's own error:
// O(1/k^2) for the continuous bilinear texture (largest measured 3.1e-7), O(perimeter / k) where
// NEAREST jumps (largest measured 8.8e-5); the tolerances are about six times these.
TEST(TextureIntegral, MatchesDenseQuadrature) {
  Pcg32 rng(41, 42);
  std::vector<Vec4> texels;
  for (int i = 0; i < 7 * 5; ++i) texels.emplace_back(rng.next1D(), rng.next1D(), rng.next1D(), rng.next1D());
  int compared = 0;
  for (WrapMode wrap : {WrapMode::Repeat, WrapMode::ClampToEdge, WrapMode::MirroredRepeat}) {
    for (bool nearest : {false, true}) {
      const Texture t = floatTexture(7, 5, texels, wrap, nearest);
      for (float size : {0.02f, 0.3f, 1.5f}) {
        for (int k = 0; k < 3; ++k) {
          const Vec2 origin = 4.f * rng.next2D() - Vec2(2.f);
          const Vec2 a = origin, b = origin + size * rng.next2D(), c = origin + size * rng.next2D();
          const glm::dvec4 reference = quadrature(t, a, b, c, 800);
          expectNear(meanOverTriangle(t, a, b, c), reference, nearest ? 5e-4 : 2e-6,
                     "wrap " + std::to_string(int(wrap)) + " nearest " + std::to_string(nearest) +
                         " size " + std::to_string(size));
          ++compared;
        }
      }
    }
  }
  EXPECT_EQ(compared, 3 * 2 * 3 * 3);
}

// Smaller than a texel: within one bilinear cell the texture is a polynomial of degree 2, whose
// mean over a triangle is exactly the mean of its values at the edge midpoints.
TEST(TextureIntegral, TriangleInsideOneTexel) {
  Pcg32 rng(43, 44);
  std::vector<Vec4> texels;
  for (int i = 0; i < 16; ++i) texels.emplace_back(rng.next1D(), rng.next1D(), rng.next1D(), 1.f);
  const Texture t = floatTexture(4, 4, texels, WrapMode::Repeat, false);
  // Cell between the texel centres (1, 1) and (2, 2): u, v in (0.375, 0.625).
  for (float size : {0.1f, 1e-3f, 1e-5f}) {
    const Vec2 a(0.4f, 0.41f), b = a + Vec2(size, 0.3f * size), c = a + Vec2(0.2f * size, size);
    const glm::dvec4 midpoints =
        (glm::dvec4(t.sample(0.5f * (a + b))) + glm::dvec4(t.sample(0.5f * (b + c))) + glm::dvec4(t.sample(0.5f * (c + a)))) / 3.0;
    expectNear(meanOverTriangle(t, a, b, c), midpoints, 1e-6, "size " + std::to_string(size));
  }
}

TEST(TextureIntegral, CollinearAndCoincidentUvs) {
  Pcg32 rng(45, 46);
  std::vector<Vec4> texels;
  for (int i = 0; i < 9; ++i) texels.emplace_back(rng.next1D(), rng.next1D(), rng.next1D(), 1.f);
  const Texture t = floatTexture(3, 3, texels, WrapMode::MirroredRepeat, false);
  // A mesh without uvs: every vertex at (0, 0).
  expectNear(meanOverTriangle(t, Vec2(0.f), Vec2(0.f), Vec2(0.f)), glm::dvec4(t.sample(Vec2(0.f))), 1e-7, "point");
  // Collinear: the segment weighted as the triangle's area maps onto it.
  const Vec2 a(0.1f, 0.2f), b(0.9f, 0.6f), c(0.5f, 0.4f);
  // Measured difference 2.0e-7 (the method's jittered quadrature against the test's grid).
  expectNear(meanOverTriangle(t, a, b, c), quadrature(t, a, b, c, 800), 2e-6, "collinear");
}

// A triangle covering the texture hundreds of times: averaged by quadrature, close to the mean
// texel of a REPEAT texture (largest measured difference 4.2e-4: the triangle covers partial
// copies along its hypotenuse, and 512^2 jittered samples).
TEST(TextureIntegral, HugeFootprintApproachesTheTextureMean) {
  Pcg32 rng(47, 48);
  std::vector<Vec4> texels;
  for (int i = 0; i < 4; ++i) texels.emplace_back(rng.next1D(), rng.next1D(), rng.next1D(), 1.f);
  const Texture t = floatTexture(2, 2, texels, WrapMode::Repeat, true);
  const Vec4 mean = meanOverTriangle(t, {0.f, 0.f}, {300.f, 0.f}, {0.f, 300.f});
  expectNear(mean, glm::dvec4(t.average()), 2e-3, "huge");
}

}  // namespace
}  // namespace pathlab
