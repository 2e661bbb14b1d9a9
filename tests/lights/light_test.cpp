// Statistical and closed-form tests of the emitters seen from a point: sampleLi / pdfLi against
// closed-form irradiance (sampleLe, power and the LightSet: light_emission_test.cpp).
#include "core/lights/light.h"
#include "core/math/rng.h"
#include "tests/lights/light_test_support.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <array>
#include <optional>
#include <vector>

namespace pathlab {
namespace {

using namespace light_test;
using test::chi2SphereTest;

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

}  // namespace
}  // namespace pathlab
