// Statistical and closed-form tests of emission, the light tracer's side of the emitters:
// sampleLe / pdfLe, power, and the power-proportional LightSet.
#include "core/lights/light.h"
#include "core/lights/light_set.h"
#include "core/math/rng.h"
#include "tests/lights/light_test_support.h"
#include "tests/support/chi2.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <map>
#include <optional>
#include <tuple>
#include <vector>

namespace pathlab {
namespace {

using namespace light_test;
using test::chi2SphereTest;

using Estimate = test::RunningStats;

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
