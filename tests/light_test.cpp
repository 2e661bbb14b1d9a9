// Statistical and closed-form tests of the emitters: sampleLi / pdfLi, sampleLe / pdfLe, power
// and the power-proportional LightSet.
#include "core/lights/light.h"
#include "core/lights/light_set.h"
#include "core/math/rng.h"
#include "tests/support/chi2.h"

#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <array>
#include <map>
#include <optional>
#include <tuple>
#include <vector>

namespace pathlab {
namespace {

using test::chi2SphereTest;

// Ten chi-square tests in this file share one family-wise significance of 1%.
const double kChi2Significance = test::sidakSignificance(0.01, 10);

using Estimate = test::RunningStats;

// Möller-Trumbore; the distance along a unit direction, if the ray hits the triangle.
std::optional<float> intersectTriangle(const Vec3& o, const Vec3& d, const std::array<Vec3, 3>& p) {
  const DVec3 e1 = DVec3(p[1] - p[0]), e2 = DVec3(p[2] - p[0]), dd = DVec3(d);
  const DVec3 q = glm::cross(dd, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-14) return std::nullopt;
  const DVec3 s = DVec3(o - p[0]);
  const double b1 = glm::dot(s, q) / det;
  const DVec3 r = glm::cross(s, e1);
  const double b2 = glm::dot(dd, r) / det;
  const double t = glm::dot(e2, r) / det;
  if (b1 < 0 || b2 < 0 || b1 + b2 > 1 || t <= 0) return std::nullopt;
  return static_cast<float>(t);
}

// Lambert's formula for the irradiance at `ref` (normal `n`) from a polygon of uniform radiance L
// lying wholly above the tangent plane: E = L/2 |sum_i Theta_i (n . Gamma_i)| (Arvo 1995, eq. 3).
double lambertIrradiance(const Vec3& ref, const Vec3& n, const std::vector<Vec3>& polygon,
                         double L) {
  double sum = 0;
  for (size_t i = 0; i < polygon.size(); ++i) {
    const DVec3 a = glm::normalize(DVec3(polygon[i] - ref));
    const DVec3 b = glm::normalize(DVec3(polygon[(i + 1) % polygon.size()] - ref));
    const double theta = std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0));
    sum += theta * glm::dot(DVec3(n), glm::normalize(glm::cross(a, b)));
  }
  return 0.5 * L * std::abs(sum);
}

// Irradiance at a point under the centre of a parallel square of half side a at height h
// (four corner rectangles of the standard differential form factor, Howell's catalogue C-11).
double squareIrradiance(double a, double h, double L) {
  const double x = a / h, s = x / std::sqrt(1 + x * x);
  return 4 * L * s * std::atan(s);
}

// KHR_lights_punctual falloff, written out again from the spec (in double; the cone's cosines
// are rounded to float first, as the light stores them).
double khrSpotFalloff(double cd, float inner, float outer) {
  const double cosInner = std::cos(inner), cosOuter = std::cos(outer);
  const double lightAngleScale = 1.0 / std::max(0.001, cosInner - cosOuter);
  const double lightAngleOffset = -cosOuter * lightAngleScale;
  const double a = std::clamp(cd * lightAngleScale + lightAngleOffset, 0.0, 1.0);
  return a * a;
}

Light makeArea(const std::array<Vec3, 3>& p, const Spectrum& L, bool twoSided,
               const Texture* tex = nullptr) {
  return Light::area(p[0], p[1], p[2], Vec2(0, 0), Vec2(1, 0), Vec2(0, 1), L, tex, twoSided);
}

const std::array<Vec3, 3> kTri = {Vec3(-0.4f, 1.f, -0.3f), Vec3(0.6f, 1.2f, -0.2f),
                                  Vec3(0.1f, 0.9f, 0.7f)};
// A large triangle just above the reference points at the origin: seen almost edge-on.
const std::array<Vec3, 3> kGrazingTri = {Vec3(-20.f, 0.05f, -20.f), Vec3(0.f, 0.05f, 30.f),
                                         Vec3(20.f, 0.05f, -20.f)};
// A large triangle off to the side and a little above the origin: seen at grazing angles, but
// far enough that the one-sample irradiance estimator has a modest variance.
const std::array<Vec3, 3> kFarGrazingTri = {Vec3(2.f, 0.3f, -4.f), Vec3(2.f, 0.3f, 4.f),
                                            Vec3(9.f, 0.3f, 0.f)};

TEST(LightArea, SampleLiPdfMatchesPdfLi) {
  Pcg32 rng(1, 2);
  for (bool twoSided : {false, true}) {
    const Light light = makeArea(kTri, Spectrum(2.f, 1.f, 0.5f), twoSided);
    const Vec3 n = glm::normalize(glm::cross(kTri[1] - kTri[0], kTri[2] - kTri[0]));
    for (const Vec3& ref : {Vec3(0.f), Vec3(0.3f, 3.f, 0.1f), Vec3(5.f, 1.f, -2.f),
                            Vec3(-0.2f, 0.2f, 0.4f)}) {
      const bool refInFront = glm::dot(ref - kTri[0], n) > 0.f;
      for (int k = 0; k < 1000; ++k) {
        const LightLiSample s = light.sampleLi(ref, rng.next2D());
        ASSERT_GT(s.pdfW, 0.f);
        ASSERT_FALSE(s.isDelta);
        EXPECT_NEAR(s.pdfW, light.pdfLi(ref, s.pLight, s.nLight), 1e-4f * s.pdfW);
        EXPECT_NEAR(glm::length(s.pLight - ref), s.dist, 1e-5f * s.dist);
        EXPECT_NEAR(glm::dot(s.wi, glm::normalize(s.pLight - ref)), 1.f, 1e-5f);
        // Li arrives from the light's front (or either side when two-sided) only.
        if (twoSided || refInFront) {
          EXPECT_EQ(s.Li, Spectrum(2.f, 1.f, 0.5f));
        } else {
          EXPECT_TRUE(isBlack(s.Li));
        }
      }
    }
  }
}

TEST(LightArea, DegenerateConfigurationsGiveZeroNotNaN) {
  const Light light = makeArea(kTri, Spectrum(1.f), false);
  // At a vertex, and in the triangle's own plane (every direction edge-on).
  const Vec3 inPlane = kTri[0] + 2.f * (kTri[1] - kTri[0]) - (kTri[2] - kTri[0]);
  Pcg32 rng(3, 4);
  for (int k = 0; k < 100; ++k) {
    for (const Vec3& ref : {kTri[0], inPlane}) {
      const LightLiSample s = light.sampleLi(ref, rng.next2D());
      EXPECT_TRUE(std::isfinite(s.pdfW));
      EXPECT_TRUE(isFinite(s.Li));
      if (s.pdfW == 0.f) {
        EXPECT_TRUE(isBlack(s.Li));
      }
    }
  }
  EXPECT_EQ(light.pdfLi(kTri[0], kTri[0], Vec3(0, 1, 0)), 0.f);
  const Light degenerate = makeArea({kTri[0], kTri[1], kTri[0]}, Spectrum(1.f), false);
  EXPECT_EQ(degenerate.power(), Spectrum(0.f));
  const LightLiSample s = degenerate.sampleLi(Vec3(0.f), Vec2(0.3f, 0.6f));
  EXPECT_EQ(s.pdfW, 0.f);
  EXPECT_TRUE(isBlack(s.Li));
  const LightLeSample le = degenerate.sampleLe(Vec2(0.3f), Vec2(0.6f));
  EXPECT_TRUE(std::isfinite(le.pdfPosA));
  EXPECT_TRUE(isBlack(le.Le));
}

TEST(LightArea, SampleLiDirectionsChi2) {
  struct Case {
    std::array<Vec3, 3> tri;
    Vec3 ref;
    const char* name;
  };
  const Case cases[] = {{kTri, Vec3(0.1f, 0.2f, 0.f), "near"},
                        {kGrazingTri, Vec3(0.f), "grazing"},
                        {kFarGrazingTri, Vec3(0.f), "far grazing"}};
  uint64_t seed = 10;
  for (const Case& c : cases) {
    const Light light = makeArea(c.tri, Spectrum(1.f), false);
    const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
      const LightLiSample s = light.sampleLi(c.ref, rng.next2D());
      if (!(s.pdfW > 0.f)) return std::nullopt;
      return s.wi;
    };
    const auto pdf = [&](const Vec3& w) -> double {
      const std::optional<float> t = intersectTriangle(c.ref, w, c.tri);
      if (!t) return 0.0;
      return light.pdfLi(c.ref, c.ref + *t * w, Vec3(0.f));
    };
    const test::Chi2Result r = chi2SphereTest(sample, pdf, 20, 40, 200000, ++seed,
                                              kChi2Significance);
    EXPECT_TRUE(r.passed) << c.name << ": " << r.message;
  }
}

TEST(LightArea, IrradianceMatchesLambertFormula) {
  struct Case {
    std::array<Vec3, 3> tri;
    Vec3 ref, n;
    bool twoSided;
  };
  // kTri faces the origin; its flipped twin is seen from the back (so it must be two-sided).
  const std::array<Vec3, 3> flipped = {kTri[0], kTri[2], kTri[1]};
  const Case cases[] = {{kTri, Vec3(0.f), glm::normalize(Vec3(0.1f, 1.f, 0.2f)), false},
                        {flipped, Vec3(0.f), Vec3(0.f, 1.f, 0.f), true},
                        {kFarGrazingTri, Vec3(0.f), Vec3(0.f, 1.f, 0.f), true},
                        {kFarGrazingTri, Vec3(0.f), glm::normalize(Vec3(1.f, 1.f, 0.f)), true}};
  const float L = 3.f;
  Pcg32 rng(5, 6);
  for (const Case& c : cases) {
    const Light light = makeArea(c.tri, Spectrum(L), c.twoSided);
    Estimate e;
    for (int k = 0; k < 200000; ++k) {
      const LightLiSample s = light.sampleLi(c.ref, rng.next2D());
      e.add(s.pdfW > 0.f ? s.Li.g * std::max(glm::dot(s.wi, c.n), 0.f) / s.pdfW : 0.0);
    }
    const double expected = lambertIrradiance(c.ref, c.n, {c.tri[0], c.tri[1], c.tri[2]}, L);
    EXPECT_NEAR(e.mean(), expected, 4 * e.standardError()) << "SE " << e.standardError();
    EXPECT_LT(e.standardError(), 0.02 * expected);  // the comparison has power
  }
}

TEST(LightArea, ParallelSquareIrradianceMatchesClosedForm) {
  // Two triangles forming the square [-a, a]^2 at height h, facing down onto the origin.
  const float a = 0.7f, h = 0.5f, L = 2.f;
  const Vec3 c00(-a, h, -a), c10(a, h, -a), c11(a, h, a), c01(-a, h, a);
  const Light t0 = makeArea({c00, c10, c11}, Spectrum(L), false);
  const Light t1 = makeArea({c00, c11, c01}, Spectrum(L), false);
  const double closedForm = squareIrradiance(a, h, L);
  // The test's Lambert formula agrees with the closed form (so it is trusted elsewhere).
  const Vec3 n(0.f, 1.f, 0.f);
  EXPECT_NEAR(lambertIrradiance(Vec3(0.f), n, {c00, c10, c11, c01}, L), closedForm,
              1e-9 * closedForm);
  Pcg32 rng(7, 8);
  Estimate e;
  for (int k = 0; k < 200000; ++k) {
    // One sample from each triangle: the sum estimates the square's irradiance.
    double sum = 0;
    for (const Light* light : {&t0, &t1}) {
      const LightLiSample s = light->sampleLi(Vec3(0.f), rng.next2D());
      if (s.pdfW > 0.f) sum += s.Li.r * std::max(glm::dot(s.wi, n), 0.f) / s.pdfW;
    }
    e.add(sum);
  }
  EXPECT_NEAR(e.mean(), closedForm, 4 * e.standardError());
  EXPECT_LT(e.standardError(), 0.01 * closedForm);
}

TEST(LightArea, RadianceAndPowerWithTexture) {
  Texture tex;
  tex.width = tex.height = 1;
  tex.texels = {Vec4(0.5f, 0.25f, 1.f, 1.f)};
  const Spectrum L(2.f, 4.f, 1.f);
  const Light one = makeArea(kTri, L, false, &tex);
  const Light two = makeArea(kTri, L, true, &tex);
  const Vec3 n = glm::normalize(glm::cross(kTri[1] - kTri[0], kTri[2] - kTri[0]));
  EXPECT_EQ(one.radiance(n, Vec2(0.3f), n), Spectrum(1.f, 1.f, 1.f));
  EXPECT_EQ(one.radiance(n, Vec2(0.3f), -n), Spectrum(0.f));
  EXPECT_EQ(two.radiance(n, Vec2(0.3f), -n), Spectrum(1.f, 1.f, 1.f));
  EXPECT_EQ(Light::point(Vec3(0.f), Spectrum(1.f)).radiance(n, Vec2(0.f), n), Spectrum(0.f));
  const float area = 0.5f * glm::length(glm::cross(kTri[1] - kTri[0], kTri[2] - kTri[0]));
  EXPECT_NEAR(one.area(), area, 1e-6f);
  const Spectrum expected = kPi * area * Spectrum(1.f);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(one.power()[c], expected[c], 1e-5f * expected[c]);
    EXPECT_NEAR(two.power()[c], 2.f * expected[c], 1e-5f * expected[c]);
  }
}

TEST(LightPunctual, SampleLi) {
  const Vec3 pos(1.f, 2.f, 3.f);
  const Spectrum I(5.f, 2.f, 1.f);
  const Light point = Light::point(pos, I);
  const float inner = 0.3f, outer = 0.6f;
  const Vec3 axis = glm::normalize(Vec3(0.f, -1.f, -0.2f));
  const Light spot = Light::spot(pos, axis, I, inner, outer);
  Pcg32 rng(9, 10);
  for (int k = 0; k < 1000; ++k) {
    const Vec3 ref = pos + Vec3(rng.next1D() - 0.5f, -rng.next1D() * 3.f, rng.next1D() - 0.5f) * 2.f;
    const Vec3 n = glm::normalize(Vec3(rng.next1D() - 0.5f, 1.f, rng.next1D() - 0.5f));
    const float d2 = glm::dot(pos - ref, pos - ref);
    const Vec3 wi = glm::normalize(pos - ref);
    for (const Light* light : {&point, &spot}) {
      const LightLiSample s = light->sampleLi(ref, rng.next2D());
      ASSERT_TRUE(s.isDelta);
      EXPECT_EQ(s.pdfW, 1.f);
      EXPECT_EQ(s.pLight, pos);
      EXPECT_NEAR(s.dist, std::sqrt(d2), 1e-5f);
      EXPECT_NEAR(glm::dot(s.wi, wi), 1.f, 1e-6f);
      EXPECT_EQ(light->pdfLi(ref, s.pLight, s.nLight), 0.f);
      // The one-sample irradiance estimate is exact: E = I cos / d^2 (times the spot falloff).
      const float falloff =
          light == &spot ? static_cast<float>(khrSpotFalloff(glm::dot(-wi, axis), inner, outer)) : 1.f;
      const float cosRef = glm::dot(n, s.wi);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(s.Li[c] * cosRef / s.pdfW, I[c] * falloff * cosRef / d2, 1e-5f * I[c] / d2);
    }
  }
  // The spec's falloff: full inside the inner cone, zero outside the outer one.
  const Frame f(axis);
  auto at = [&](float theta) { return f.toWorld(Vec3(std::sin(theta), 0.f, std::cos(theta))); };
  EXPECT_EQ(spot.intensity(at(0.1f)), I);
  EXPECT_EQ(spot.intensity(at(0.7f)), Spectrum(0.f));
  EXPECT_NEAR(spot.intensity(at(0.45f)).r, I.r * khrSpotFalloff(std::cos(0.45f), inner, outer), 1e-5f);
  EXPECT_GT(spot.intensity(at(0.45f)).r, 0.f);
  EXPECT_LT(spot.intensity(at(0.45f)).r, I.r);
  // Coincident reference point: no NaN, zero density.
  const LightLiSample s = point.sampleLi(pos, Vec2(0.5f));
  EXPECT_EQ(s.pdfW, 0.f);
  EXPECT_TRUE(isBlack(s.Li));
}

TEST(LightDirectional, SampleLi) {
  const Vec3 dir = glm::normalize(Vec3(0.3f, -1.f, 0.2f));
  const Spectrum E(1.f, 2.f, 3.f);
  const SceneBounds bounds{Vec3(1.f, 0.f, 0.f), 4.f};
  const Light light = Light::directional(dir, E, bounds);
  EXPECT_TRUE(light.isInfinite());
  EXPECT_TRUE(light.isDeltaDirection());
  for (const Vec3& ref : {Vec3(0.f), Vec3(3.f, 1.f, -2.f)}) {
    const LightLiSample s = light.sampleLi(ref, Vec2(0.2f, 0.7f));
    EXPECT_TRUE(s.isDelta);
    EXPECT_EQ(s.pdfW, 1.f);
    EXPECT_EQ(s.Li, E);
    EXPECT_NEAR(glm::dot(s.wi, -dir), 1.f, 1e-6f);
    EXPECT_TRUE(std::isinf(s.dist));
    EXPECT_NEAR(glm::length(s.pLight - (ref - dir * 8.f)), 0.f, 1e-5f);
  }
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(light.power()[c], kPi * 16.f * E[c], 1e-4f * E[c]);
}

// All lights of the emission tests, with names for messages.
std::vector<std::pair<const char*, Light>> emissionLights() {
  return {{"area", makeArea(kTri, Spectrum(2.f, 1.f, 3.f), false)},
          {"area two-sided", makeArea(kTri, Spectrum(2.f, 1.f, 3.f), true)},
          {"point", Light::point(Vec3(1.f, 2.f, 3.f), Spectrum(5.f, 2.f, 1.f))},
          {"spot", Light::spot(Vec3(1.f, 2.f, 3.f), glm::normalize(Vec3(0.3f, -1.f, 0.2f)),
                               Spectrum(5.f, 2.f, 1.f), 0.3f, 0.7f)},
          {"spot hard", Light::spot(Vec3(0.f), Vec3(0.f, 0.f, 1.f), Spectrum(1.f), 0.5f, 0.5f)},
          {"directional", Light::directional(glm::normalize(Vec3(0.3f, -1.f, 0.2f)),
                                             Spectrum(1.f, 2.f, 3.f),
                                             SceneBounds{Vec3(1.f, 0.f, 0.f), 4.f})}};
}

TEST(LightEmission, SampleLePdfsMatchPdfLe) {
  Pcg32 rng(11, 12);
  for (const auto& [name, light] : emissionLights()) {
    for (int k = 0; k < 2000; ++k) {
      const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
      ASSERT_GT(s.pdfPosA, 0.f) << name;
      EXPECT_NEAR(glm::length(s.ray.d), 1.f, 1e-5f) << name;
      const EmissionPdf p = light.pdfLe(s.ray.o, s.n, s.ray.d);
      EXPECT_NEAR(p.pdfPosA, s.pdfPosA, 1e-5f * s.pdfPosA) << name;
      EXPECT_NEAR(p.pdfDirW, s.pdfDirW, 1e-4f * s.pdfDirW) << name;
      if (light.type() == LightType::Area) {
        EXPECT_NEAR(p.pdfPosA, 1.f / light.area(), 1e-5f);
        EXPECT_EQ(s.Le, light.radiance(s.n, Vec2(0.f), s.ray.d)) << name;
      }
      if (light.isDeltaPosition()) {
        EXPECT_EQ(s.Le, light.intensity(s.ray.d)) << name;
        EXPECT_EQ(s.ray.o, light.sampleLi(Vec3(9.f), Vec2(0.5f)).pLight) << name;
      }
    }
  }
}

TEST(LightEmission, SampleLeDirectionsChi2) {
  uint64_t seed = 100;
  for (const auto& [name, light] : emissionLights()) {
    if (light.isDeltaDirection()) continue;
    // Positions do not change the direction densities; fix the origin for the pdf.
    const LightLeSample first = light.sampleLe(Vec2(0.3f), Vec2(0.5f));
    const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
      const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
      if (!(s.pdfDirW > 0.f)) return std::nullopt;
      return s.ray.d;
    };
    const auto pdf = [&](const Vec3& w) -> double {
      return light.pdfLe(first.ray.o, first.n, w).pdfDirW;
    };
    const test::Chi2Result r = chi2SphereTest(sample, pdf, 16, 32, 100000, ++seed,
                                              kChi2Significance);
    EXPECT_TRUE(r.passed) << name << ": " << r.message;
  }
}

TEST(LightArea, SampleLePositionsUniform) {
  // Midpoint subdivision of the triangle into n^2 congruent cells, counted from barycentrics.
  const int n = 8, cells = n * n, samples = 128000;
  const Light light = makeArea(kTri, Spectrum(1.f), true);
  const DVec3 e1 = DVec3(kTri[1] - kTri[0]), e2 = DVec3(kTri[2] - kTri[0]);
  std::map<std::tuple<int, int, int>, int> counts;
  Pcg32 rng(13, 14);
  for (int k = 0; k < samples; ++k) {
    const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
    const DVec3 q = DVec3(s.ray.o - kTri[0]);
    // Solve q = b1 e1 + b2 e2 by least squares (q lies in the plane).
    const double a11 = glm::dot(e1, e1), a12 = glm::dot(e1, e2), a22 = glm::dot(e2, e2);
    const double r1 = glm::dot(q, e1), r2 = glm::dot(q, e2), det = a11 * a22 - a12 * a12;
    const double b1 = (r1 * a22 - r2 * a12) / det, b2 = (r2 * a11 - r1 * a12) / det;
    ASSERT_GT(b1, -1e-5);
    ASSERT_GT(b2, -1e-5);
    ASSERT_LT(b1 + b2, 1 + 1e-5);
    const double x = std::clamp(b1, 0.0, 1.0) * n, y = std::clamp(b2, 0.0, 1.0) * n;
    int i = std::min(static_cast<int>(x), n - 1), j = std::min(static_cast<int>(y), n - 1 - i);
    const int upper = (x - i) + (y - j) > 1.0 && i + j < n - 1 ? 1 : 0;
    ++counts[{i, j, upper}];
  }
  ASSERT_LE(static_cast<int>(counts.size()), cells);
  const double expected = static_cast<double>(samples) / cells;
  double chi2 = 0;
  for (const auto& [cell, c] : counts) chi2 += (c - expected) * (c - expected) / expected;
  chi2 += (cells - static_cast<int>(counts.size())) * expected;  // empty cells
  const double p = test::regularizedGammaQ(0.5 * (cells - 1), 0.5 * chi2);
  EXPECT_GT(p, kChi2Significance) << "chi2 = " << chi2 << " over " << cells << " cells";
}

TEST(LightEmission, PowerMatchesMonteCarlo) {
  Pcg32 rng(15, 16);
  for (const auto& [name, light] : emissionLights()) {
    Estimate e;
    for (int k = 0; k < 100000; ++k) {
      const LightLeSample s = light.sampleLe(rng.next2D(), rng.next2D());
      const double pdf = static_cast<double>(s.pdfPosA) * s.pdfDirW;
      if (!(pdf > 0.0)) {
        e.add(0.0);
        continue;
      }
      // Flux = integral of Le |cos| over the light's area and directions; punctual lights have
      // no area and no cosine, and the directional light's disk is perpendicular to it.
      const double cosine = light.type() == LightType::Area ? absDot(s.n, s.ray.d) : 1.0;
      e.add(luminance(s.Le) * cosine / pdf);
    }
    const double expected = luminance(light.power());
    // Area, point and directional estimators are constant (zero SE); the spot's varies.
    EXPECT_NEAR(e.mean(), expected, 4 * e.standardError() + 1e-5 * expected) << name;
  }
}

TEST(LightSpot, PowerIsExactFalloffIntegral) {
  for (auto [inner, outer] : {std::pair{0.f, 0.5f}, {0.3f, 0.7f}, {0.5f, 0.5f}, {1.f, 1.5f},
                              {0.f, 0.02f}}) {
    const Light spot = Light::spot(Vec3(0.f), Vec3(0.f, 0.f, 1.f), Spectrum(1.f), inner, outer);
    // Midpoint rule over cos theta on [cos outer, 1] (the falloff is zero below).
    const int steps = 200000;
    const double c0 = std::cos(outer);
    double integral = 0;
    for (int i = 0; i < steps; ++i) {
      const double c = c0 + (1 - c0) * (i + 0.5) / steps;
      integral += khrSpotFalloff(c, inner, outer);
    }
    integral *= 2 * kPi * (1 - c0) / steps;
    EXPECT_NEAR(spot.power().r, integral, 1e-4 * integral) << inner << " " << outer;
  }
}

TEST(LightSet, SelectionProportionalToPower) {
  std::vector<Light> lights = {
      Light::point(Vec3(0.f), Spectrum(1.f)),
      makeArea(kTri, Spectrum(3.f, 1.f, 0.f), false),
      Light::point(Vec3(1.f), Spectrum(0.f)),  // no power: never chosen
      Light::spot(Vec3(0.f), Vec3(0.f, 0.f, 1.f), Spectrum(0.f, 0.f, 20.f), 0.2f, 0.9f),
      Light::directional(Vec3(0.f, -1.f, 0.f), Spectrum(0.5f), SceneBounds{Vec3(0.f), 1.f})};
  std::vector<std::vector<int>> triangleLight = {{-1, 1}, {}};
  const LightSet set(lights, triangleLight);
  ASSERT_EQ(set.size(), lights.size());
  double total = 0;
  for (const Light& l : lights) total += luminance(l.power());
  for (size_t i = 0; i < lights.size(); ++i)
    EXPECT_NEAR(set.pmf(static_cast<int>(i)), luminance(lights[i].power()) / total, 1e-6);
  EXPECT_EQ(set.pmf(2), 0.f);

  const int samples = 200000;
  std::vector<int> counts(lights.size(), 0);
  Pcg32 rng(17, 18);
  Estimate remapped;
  for (int k = 0; k < samples; ++k) {
    float pmf = 0, u2 = -1;
    const int i = set.sample(rng.next1D(), &pmf, &u2);
    ASSERT_GE(i, 0);
    ASSERT_LT(i, static_cast<int>(lights.size()));
    ASSERT_EQ(pmf, set.pmf(i));
    ASSERT_GE(u2, 0.f);
    ASSERT_LT(u2, 1.f);
    remapped.add(u2);
    ++counts[static_cast<size_t>(i)];
  }
  EXPECT_EQ(counts[2], 0);
  double chi2 = 0;
  int dof = -1;
  for (size_t i = 0; i < lights.size(); ++i) {
    const double expected = samples * set.pmf(static_cast<int>(i));
    if (expected == 0) continue;
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
    ++dof;
  }
  EXPECT_GT(test::regularizedGammaQ(0.5 * dof, 0.5 * chi2), kChi2Significance) << chi2;
  EXPECT_NEAR(remapped.mean(), 0.5, 4 * remapped.standardError());  // uniform within the chosen bin

  EXPECT_EQ(set.lightOfTriangle(0, 1), 1);
  EXPECT_EQ(set.lightOfTriangle(0, 0), -1);
  EXPECT_EQ(set.lightOfTriangle(0, 2), -1);
  EXPECT_EQ(set.lightOfTriangle(1, 0), -1);
  EXPECT_EQ(set.lightOfTriangle(7, 0), -1);
}

TEST(LightSet, EmptyOrPowerlessChoosesNothing) {
  float pmf = 1;
  EXPECT_EQ(LightSet().sample(0.5f, &pmf), -1);
  EXPECT_EQ(pmf, 0.f);
  const LightSet dark({Light::point(Vec3(0.f), Spectrum(0.f))}, {});
  pmf = 1;
  EXPECT_EQ(dark.sample(0.5f, &pmf), -1);
  EXPECT_EQ(pmf, 0.f);
  EXPECT_TRUE(LightSet().empty());
}

}  // namespace
}  // namespace pathlab
