// Statistical tests of the glTF BSDF (chi-square, consistency, reciprocity, energy, deltas) and of
// the chi-square tool itself.
#include "core/bsdf/bsdf.h"
#include "core/bsdf/fresnel.h"
#include "core/sampling/warp.h"
#include "tests/support/chi2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using namespace pathlab;

namespace {

const Vec3 kNg(0.f, 0.f, 1.f);
const Vec3 kTiltedNs = glm::normalize(Vec3(0.25f, -0.15f, 1.f));

Vec3 direction(float cosTheta, float phi) {
  const float sinTheta = safeSqrt(1.f - cosTheta * cosTheta);
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

MaterialPoint dielectric(Spectrum base, float roughness) {
  MaterialPoint m;
  m.baseColor = base;
  m.roughness = roughness;
  return m;
}
MaterialPoint lambert(Spectrum base) {
  MaterialPoint m = dielectric(base, 0.5f);
  m.specularFactor = 0.f;
  return m;
}
MaterialPoint metal(Spectrum f0, float roughness) {
  MaterialPoint m = dielectric(f0, roughness);
  m.metallic = 1.f;
  return m;
}
MaterialPoint glass(Spectrum tint, float roughness, float ior = 1.5f) {
  MaterialPoint m = dielectric(tint, roughness);
  m.transmission = 1.f;
  m.ior = ior;
  return m;
}
MaterialPoint mixture(Spectrum base) {
  MaterialPoint m = dielectric(base, 0.5f);
  m.metallic = 0.5f;
  m.transmission = 0.5f;
  return m;
}
MaterialPoint tintedSpecular(Spectrum base) {
  MaterialPoint m = dielectric(base, 0.4f);
  m.ior = 1.33f;
  m.specularFactor = 0.6f;
  m.specularColor = Spectrum(1.f, 0.5f, 2.f);
  return m;
}

const Spectrum kColour(0.7f, 0.45f, 0.2f);
const Spectrum kGold(1.f, 0.78f, 0.34f);
const Spectrum kTint(0.9f, 0.95f, 1.f);

struct Case {
  std::string name;
  MaterialPoint material;
  Vec3 wo;
  bool tilted = false;
};

// The material table of the statistical tests; ng = +z, so z < 0 is inside transmissive solids.
std::vector<Case> cases(bool white) {
  const Spectrum c = white ? Spectrum(1.f) : kColour;
  const Spectrum g = white ? Spectrum(1.f) : kGold;
  const Spectrum t = white ? Spectrum(1.f) : kTint;
  std::vector<Case> list;
  auto add = [&](const std::string& name, const MaterialPoint& m, std::vector<float> cosines,
                 bool tilted = false) {
    for (float cosTheta : cosines) {
      list.push_back({name + " cos " + std::to_string(cosTheta), m,
                      direction(cosTheta, 0.7f + 2.f * cosTheta), tilted});
    }
  };
  add("lambert", lambert(Spectrum(1.f)), {0.9f, 0.05f});
  add("specularFactor 0", lambert(c), {0.5f});
  add("plastic r0.05", dielectric(c, 0.05f), {0.9f, 0.5f, 0.05f});
  add("plastic r0.3", dielectric(c, 0.3f), {0.9f, 0.05f});
  add("plastic r0.3 tilted", dielectric(c, 0.3f), {0.5f}, true);
  add("plastic r1", dielectric(c, 1.f), {0.5f, 0.05f});
  add("tinted specular", tintedSpecular(c), {0.7f, 0.1f});
  add("metal r0.05", metal(g, 0.05f), {0.9f, 0.05f});
  add("metal r0.3", metal(g, 0.3f), {0.5f, 0.05f});
  add("metal r0.3 tilted", metal(g, 0.3f), {0.9f}, true);
  add("metal r1", metal(g, 1.f), {0.5f});
  add("glass r0.1 outside", glass(t, 0.1f), {0.9f, 0.3f});
  add("glass r0.1 inside", glass(t, 0.1f), {-0.9f, -0.5f});
  add("glass r0.5 outside", glass(t, 0.5f), {0.7f, 0.05f});
  add("glass r0.5 inside", glass(t, 0.5f), {-0.8f, -0.3f});
  add("glass r0.5 tilted", glass(t, 0.5f), {0.6f, -0.6f}, true);
  add("mixture", mixture(c), {0.8f, 0.2f});
  add("mixture tilted", mixture(c), {0.6f}, true);
  return list;
}

Bsdf makeBsdf(const Case& c) { return Bsdf(c.tilted ? kTiltedNs : kNg, kNg, c.material); }

const char* modeName(TransportMode mode) {
  return mode == TransportMode::Radiance ? "radiance" : "importance";
}
constexpr TransportMode kModes[] = {TransportMode::Radiance, TransportMode::Importance};

// |a - b| <= rel max(|a|, |b|) + abs per channel.
::testing::AssertionResult near(const Spectrum& a, const Spectrum& b, float rel, float abs = 1e-6f) {
  for (int k = 0; k < 3; ++k) {
    if (!(std::abs(a[k] - b[k]) <= rel * glm::max(std::abs(a[k]), std::abs(b[k])) + abs)) {
      return ::testing::AssertionFailure() << "(" << a.r << ", " << a.g << ", " << a.b << ") vs ("
                                           << b.r << ", " << b.g << ", " << b.b << ")";
    }
  }
  return ::testing::AssertionSuccess();
}
::testing::AssertionResult near(float a, float b, float rel, float abs = 1e-6f) {
  return near(Spectrum(a), Spectrum(b), rel, abs);
}

// Refractive index on the side of w (ng = +z points outside).
float sideIor(const Vec3& w, float ior) { return w.z > 0.f ? 1.f : ior; }

}  // namespace

// ---------------------------------------------------------------------------------------------
// The chi-square tool on samplers whose answer is known.

TEST(Chi2Tool, IncompleteGammaMatchesReferenceValues) {
  // Chi-square survival function: k = 4, x = 10 and k = 100, x = 120 (mpmath).
  EXPECT_NEAR(test::regularizedGammaQ(2.0, 5.0), 0.040427681994512805, 1e-12);
  EXPECT_NEAR(test::regularizedGammaQ(50.0, 60.0), 0.0844066810936918, 1e-10);
  EXPECT_NEAR(test::regularizedGammaQ(0.5, 0.5 * 3.841458820694124), 0.05, 1e-10);
}

TEST(Chi2Tool, AcceptsCorrectSamplers) {
  const test::Chi2Result cosine = test::chi2SphereTest(
      [](Pcg32& rng) -> std::optional<Vec3> { return sampleCosineHemisphere(rng.next2D()); },
      [](const Vec3& w) { return double(cosineHemispherePdf(w.z)); }, 10, 20, 200000, 1);
  EXPECT_TRUE(cosine.passed) << cosine.message;
  // A narrow tilted cone (support far smaller than a cell) with 30% of samples rejected.
  const Frame frame(glm::normalize(Vec3(1.f, 2.f, 0.3f)));
  const float cosMax = 0.995f;
  const test::Chi2Result cone = test::chi2SphereTest(
      [&](Pcg32& rng) -> std::optional<Vec3> {
        if (rng.next1D() < 0.3f) return std::nullopt;
        return frame.toWorld(sampleUniformCone(rng.next2D(), cosMax));
      },
      [&](const Vec3& w) {
        return frame.toLocal(w).z >= cosMax ? 0.7 * uniformConePdf(cosMax) : 0.0;
      },
      10, 20, 200000, 2);
  EXPECT_TRUE(cone.passed) << cone.message;
}

TEST(Chi2Tool, RejectsWrongDensityAndWrongMass) {
  const test::Chi2Result shape = test::chi2SphereTest(
      [](Pcg32& rng) -> std::optional<Vec3> { return sampleCosineHemisphere(rng.next2D()); },
      [](const Vec3& w) { return w.z > 0.f ? double(kInv2Pi) : 0.0; }, 10, 20, 20000, 3);
  EXPECT_FALSE(shape.passed) << shape.message;
  EXPECT_NE(shape.message.find("worst cells"), std::string::npos);
  // Right shape, but the sampler absorbs 3% that the density claims to deliver.
  const test::Chi2Result mass = test::chi2SphereTest(
      [](Pcg32& rng) -> std::optional<Vec3> {
        if (rng.next1D() < 0.03f) return std::nullopt;
        return sampleCosineHemisphere(rng.next2D());
      },
      [](const Vec3& w) { return double(cosineHemispherePdf(w.z)); }, 10, 20, 200000, 4);
  EXPECT_FALSE(mass.passed) << mass.message;
}

// ---------------------------------------------------------------------------------------------
// 1. Sampled directions follow pdf (delta samples count as rejected).

TEST(BsdfSampling, ChiSquareMatchesPdf) {
  const std::vector<Case> list = cases(false);
  const double significance = test::sidakSignificance(0.01, 2 * static_cast<int>(list.size()));
  uint64_t seed = 100;
  for (const Case& c : list) {
    const Bsdf bsdf = makeBsdf(c);
    for (TransportMode mode : kModes) {
      const test::Chi2Result r = test::chi2SphereTest(
          [&](Pcg32& rng) -> std::optional<Vec3> {
            const Vec2 u = rng.next2D();
            const std::optional<BsdfSample> s = bsdf.sample(c.wo, u, rng.next1D(), mode);
            if (!s || s->isDelta) return std::nullopt;
            return s->wi;
          },
          [&](const Vec3& wi) { return double(bsdf.pdf(c.wo, wi, mode)); }, 12, 24, 100000,
          ++seed, significance);
      EXPECT_TRUE(r.passed) << c.name << " (" << modeName(mode) << "): " << r.message;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 2. sample, eval and pdf agree, forward and reverse.

TEST(BsdfSampling, SampleEvalPdfConsistent) {
  for (const Case& c : cases(false)) {
    const Bsdf bsdf = makeBsdf(c);
    for (TransportMode mode : kModes) {
      Pcg32 rng(7, 11);
      int nonDelta = 0;
      for (int k = 0; k < 2000; ++k) {
        const Vec2 u = rng.next2D();
        const std::optional<BsdfSample> s = bsdf.sample(c.wo, u, rng.next1D(), mode);
        if (!s) continue;
        ASSERT_TRUE(isValidContribution(s->f)) << c.name;
        ASSERT_TRUE(std::isfinite(s->pdfFwdW) && s->pdfFwdW > 0.f) << c.name;
        ASSERT_TRUE(std::isfinite(s->pdfRevW) && s->pdfRevW >= 0.f) << c.name;
        ASSERT_NEAR(glm::length(s->wi), 1.f, 1e-5f);
        EXPECT_EQ(s->isTransmission, (glm::dot(s->wi, kNg) > 0.f) != (c.wo.z > 0.f)) << c.name;
        if (s->isDelta) continue;
        ++nonDelta;
        const BsdfEval e = bsdf.eval(c.wo, s->wi, mode);
        ASSERT_TRUE(near(s->f, e.f, 1e-4f)) << c.name << " " << modeName(mode);
        ASSERT_TRUE(near(s->pdfFwdW, e.pdfFwdW, 1e-4f)) << c.name;
        ASSERT_TRUE(near(s->pdfFwdW, bsdf.pdf(c.wo, s->wi, mode), 1e-4f)) << c.name;
        ASSERT_TRUE(near(s->pdfRevW, e.pdfRevW, 1e-4f)) << c.name;
        ASSERT_TRUE(near(e.pdfRevW, bsdf.pdf(s->wi, c.wo, mode), 1e-4f)) << c.name;
        // The BPT's misWeight takes a vertex's reverse density from the other subpath's transport
        // mode: sampling densities must not depend on the mode.
        const TransportMode other = mode == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
        ASSERT_TRUE(near(bsdf.pdf(c.wo, s->wi, other), s->pdfFwdW, 1e-5f)) << c.name;
        ASSERT_TRUE(near(bsdf.pdf(s->wi, c.wo, other), s->pdfRevW, 1e-5f)) << c.name;
      }
      EXPECT_GT(nonDelta, 100) << c.name;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 3. Reciprocity: f(wo, wi) / eta_o^2 = f(wi, wo) / eta_i^2 in radiance mode (Veach 1997,
// eq. 5.14), which is plain symmetry for reflection; the adjoint is the radiance BSDF with its
// arguments swapped, times Veach's shading-normal factor (eq. 5.19).

TEST(BsdfReciprocity, GeneralizedReciprocityAndAdjoint) {
  for (const Case& c : cases(false)) {
    const Bsdf bsdf = makeBsdf(c);
    Pcg32 rng(3, 5);
    int nonZeroReflection = 0, nonZeroTransmission = 0;
    for (int k = 0; k < 4000; ++k) {
      const Vec3 wo = sampleUniformSphere(rng.next2D());
      // Half the pairs near the specular configurations, where peaky lobes are non-zero.
      Vec3 wi = sampleUniformSphere(rng.next2D());
      if (k % 2 == 0) {
        const Vec3 n = bsdf.shadingFrame().n;
        const Vec3 around = (k % 4 == 0) ? reflect(wo, n * (glm::dot(wo, n) > 0.f ? 1.f : -1.f))
                                         : -wo;
        wi = glm::normalize(around + 0.3f * c.material.roughness * sampleUniformSphere(rng.next2D()));
      }
      const Spectrum fRad = bsdf.eval(wo, wi, TransportMode::Radiance).f;
      const Spectrum fRadSwapped = bsdf.eval(wi, wo, TransportMode::Radiance).f;
      const Spectrum fImp = bsdf.eval(wo, wi, TransportMode::Importance).f;
      const float etaO = sideIor(wo, c.material.ior), etaI = sideIor(wi, c.material.ior);
      const float corr = absDot(wo, bsdf.shadingFrame().n) * absDot(wi, kNg) /
                         (absDot(wo, kNg) * absDot(wi, bsdf.shadingFrame().n));
      ASSERT_TRUE(near(fImp, fRadSwapped * corr, 2e-4f)) << c.name << " wo.z " << wo.z;
      if (c.tilted) continue;
      ASSERT_TRUE(near(fRad / (etaO * etaO), fRadSwapped / (etaI * etaI), 2e-4f))
          << c.name << " wo.z " << wo.z << " wi.z " << wi.z;
      // Hence the adjoint differs from the radiance BSDF by (eta_i / eta_o)^2 (Veach, sec. 5.2).
      ASSERT_TRUE(near(fImp, fRad * sqr(etaI / etaO), 2e-4f)) << c.name << " wo.z " << wo.z;
      if (!isBlack(fRad)) ++(wo.z * wi.z > 0.f ? nonZeroReflection : nonZeroTransmission);
    }
    if (!c.tilted) {
      EXPECT_GT(nonZeroReflection, 50) << c.name;
      if (c.material.transmission > 0.f) {
        EXPECT_GT(nonZeroTransmission, 50) << c.name;
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 4. Energy: the albedo for light arriving along wo, integral of f(wo -> wi) |cos| dwi, is at
// most 1. In importance mode f is that directly; in radiance mode f(wi -> wo) relates to it by
// (eta_i / eta_o)^2 on transmission.

struct Albedo {
  double mean = 0, standardError = 0;
};
Albedo albedo(const Bsdf& bsdf, const Vec3& wo, TransportMode mode, float ior, int n,
              uint64_t seed) {
  Pcg32 rng(seed, 17);
  double sum = 0, sum2 = 0;
  for (int k = 0; k < n; ++k) {
    const Vec2 u = rng.next2D();
    const std::optional<BsdfSample> s = bsdf.sample(wo, u, rng.next1D(), mode);
    if (!s) continue;
    double w = maxComponent(s->f) * absDot(s->wi, bsdf.shadingFrame().n) / s->pdfFwdW;
    if (mode == TransportMode::Radiance && s->isTransmission)
      w *= sqr(sideIor(s->wi, ior) / sideIor(wo, ior));
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

TEST(BsdfEnergy, AlbedoAtMostOne) {
  uint64_t seed = 1;
  for (const Case& c : cases(true)) {
    if (c.tilted) continue;  // shading normals do not conserve energy
    const Bsdf bsdf = makeBsdf(c);
    for (TransportMode mode : kModes) {
      const Albedo a = albedo(bsdf, c.wo, mode, c.material.ior, 50000, ++seed);
      EXPECT_LE(a.mean, 1.0 + 4.0 * a.standardError + 1e-5)
          << c.name << " (" << modeName(mode) << "): " << a.mean << " +- " << a.standardError;
      EXPECT_GT(a.mean, 0.0) << c.name;
    }
  }
}

TEST(BsdfEnergy, WhiteLambertianAndPerfectMirrorsReflectEverything) {
  const Bsdf white(kNg, kNg, lambert(Spectrum(1.f)));
  const Bsdf mirror(kTiltedNs, kNg, metal(Spectrum(1.f), 0.f));
  const Bsdf smoothGlass(kNg, kNg, glass(Spectrum(1.f), 0.f));
  for (float cosTheta : {0.95f, 0.5f, 0.05f}) {
    const Vec3 wo = direction(cosTheta, 1.f);
    const Albedo a = albedo(white, wo, TransportMode::Radiance, 1.5f, 20000, 3);
    EXPECT_NEAR(a.mean, 1.0, 4.0 * a.standardError + 1e-5) << cosTheta;
    const Albedo m = albedo(mirror, wo, TransportMode::Radiance, 1.5f, 1000, 4);
    EXPECT_NEAR(m.mean, 1.0, 1e-5) << cosTheta;
    EXPECT_NEAR(m.standardError, 0.0, 1e-6) << cosTheta;
    for (float side : {1.f, -1.f}) {
      const Albedo g = albedo(smoothGlass, side * wo, TransportMode::Importance, 1.5f, 1000, 5);
      EXPECT_NEAR(g.mean, 1.0, 1e-5) << cosTheta << " side " << side;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 5. Delta lobes.

TEST(BsdfDelta, SmoothMetalIsAMirror) {
  for (const Vec3& ns : {kNg, kTiltedNs}) {
    const Bsdf bsdf(ns, kNg, metal(kGold, 0.01f));
    EXPECT_FALSE(bsdf.hasNonDelta());
    const Vec3 wo = direction(0.6f, 2.f);
    Pcg32 rng(9, 1);
    for (int k = 0; k < 100; ++k) {
      const std::optional<BsdfSample> s = bsdf.sample(wo, rng.next2D(), rng.next1D(),
                                                      TransportMode::Radiance);
      ASSERT_TRUE(s);
      EXPECT_TRUE(s->isDelta);
      EXPECT_FALSE(s->isTransmission);
      EXPECT_LT(glm::length(s->wi - reflect(wo, ns)), 1e-5f);
      EXPECT_FLOAT_EQ(s->pdfFwdW, 1.f);
      const Spectrum weight = s->f * absDot(s->wi, ns) / s->pdfFwdW;
      EXPECT_TRUE(near(weight, fresnelSchlick(kGold, 1.f, glm::dot(wo, ns)), 1e-5f));
    }
    EXPECT_TRUE(isBlack(bsdf.eval(wo, reflect(wo, ns), TransportMode::Radiance).f));
    EXPECT_EQ(bsdf.pdf(wo, reflect(wo, ns), TransportMode::Radiance), 0.f);
  }
}

TEST(BsdfDelta, SmoothGlassRefractsBySnellAndReflectsTotallyInside) {
  const float ior = 1.5f;
  const Bsdf bsdf(kNg, kNg, glass(Spectrum(1.f), 0.f, ior));
  EXPECT_FALSE(bsdf.hasNonDelta());
  // Outside: reflection with probability F, refraction along Snell's law otherwise.
  for (float cosTheta : {0.9f, 0.4f, 0.1f}) {
    const Vec3 wo = direction(cosTheta, 0.5f);
    const float fr = fresnelDielectric(cosTheta, ior);
    const int n = 20000;
    int reflected = 0;
    Pcg32 rng(21, 2);
    for (int k = 0; k < n; ++k) {
      const std::optional<BsdfSample> s =
          bsdf.sample(wo, rng.next2D(), rng.next1D(), TransportMode::Radiance);
      ASSERT_TRUE(s && s->isDelta);
      if (!s->isTransmission) {
        ++reflected;
        EXPECT_LT(glm::length(s->wi - reflect(wo, kNg)), 1e-5f);
        continue;
      }
      const float sinI = glm::length(Vec2(wo)), sinT = glm::length(Vec2(s->wi));
      EXPECT_NEAR(sinI, ior * sinT, 1e-5f);
      EXPECT_LT(s->wi.z, 0.f);
      EXPECT_LT(glm::length(glm::normalize(Vec2(s->wi)) + glm::normalize(Vec2(wo))), 1e-4f);
      // Radiance mode: (1 - F) / eta^2 per unit probability of refraction.
      EXPECT_NEAR(s->f.r * std::abs(s->wi.z) / s->pdfFwdW, 1.f / (ior * ior), 1e-5f);
    }
    const double se = std::sqrt(fr * (1.0 - fr) / n);
    EXPECT_NEAR(double(reflected) / n, fr, 4.0 * se + 1e-4) << cosTheta;
  }
  // Inside, beyond the critical angle (sin > 1 / 1.5): reflection only, with weight 1.
  for (float cosTheta : {0.7f, 0.3f, 0.05f}) {
    const Vec3 wo = -direction(cosTheta, 0.5f);
    Pcg32 rng(22, 3);
    for (int k = 0; k < 200; ++k) {
      const std::optional<BsdfSample> s =
          bsdf.sample(wo, rng.next2D(), rng.next1D(), TransportMode::Radiance);
      ASSERT_TRUE(s && s->isDelta);
      EXPECT_FALSE(s->isTransmission);
      EXPECT_LT(s->wi.z, 0.f);
      EXPECT_NEAR(s->f.r * std::abs(s->wi.z) / s->pdfFwdW, 1.f, 1e-5f);
    }
  }
  // Inside, below the critical angle: both events occur.
  const Vec3 wo = -direction(0.9f, 0.5f);
  Pcg32 rng(23, 4);
  int transmitted = 0;
  for (int k = 0; k < 1000; ++k) {
    const std::optional<BsdfSample> s = bsdf.sample(wo, rng.next2D(), rng.next1D(),
                                                    TransportMode::Importance);
    ASSERT_TRUE(s);
    transmitted += s->isTransmission;
  }
  EXPECT_GT(transmitted, 900);
  EXPECT_LT(transmitted, 1000);
}

// ---------------------------------------------------------------------------------------------
// 6. specularFactor = 0 is exactly Lambert.

TEST(BsdfSpecularFactor, ZeroGivesExactlyLambert) {
  for (float roughness : {0.f, 0.5f}) {
    MaterialPoint m = lambert(kColour);
    m.roughness = roughness;
    const Bsdf bsdf(kNg, kNg, m);
    EXPECT_TRUE(bsdf.hasNonDelta());
    Pcg32 rng(5, 5);
    for (int k = 0; k < 200; ++k) {
      const Vec3 wo = sampleCosineHemisphere(rng.next2D());
      const Vec3 wi = sampleCosineHemisphere(rng.next2D());
      if (wo.z < 1e-3f || wi.z < 1e-3f) continue;
      const BsdfEval e = bsdf.eval(wo, wi, TransportMode::Radiance);
      EXPECT_EQ(e.f, kColour * kInvPi);
      EXPECT_NEAR(e.pdfFwdW, wi.z * kInvPi, 1e-6f);
      const std::optional<BsdfSample> s =
          bsdf.sample(wo, rng.next2D(), rng.next1D(), TransportMode::Radiance);
      ASSERT_TRUE(s);
      EXPECT_FALSE(s->isDelta);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Robustness: no NaN, Inf or negative value anywhere, grazing and back-facing included.

TEST(BsdfRobustness, FiniteNonNegativeEverywhere) {
  Pcg32 rng(77, 0);
  for (int k = 0; k < 20000; ++k) {
    MaterialPoint m;
    m.baseColor = Spectrum(rng.next1D(), rng.next1D(), rng.next1D());
    m.metallic = rng.next1D() < 0.3f ? 0.f : rng.next1D();
    m.roughness = rng.next1D() < 0.2f ? 0.f : rng.next1D();
    m.ior = 1.f + 1.5f * rng.next1D();
    m.specularFactor = rng.next1D();
    m.transmission = rng.next1D() < 0.5f ? 0.f : rng.next1D();
    const Vec3 ns = glm::normalize(kNg + 0.5f * sampleUniformSphere(rng.next2D()));
    const Bsdf bsdf(ns, kNg, m);
    // Grazing directions a quarter of the time.
    auto randomDirection = [&] {
      Vec3 w = sampleUniformSphere(rng.next2D());
      if (rng.next1D() < 0.25f) w = glm::normalize(Vec3(w.x, w.y, 1e-4f * (w.z - 0.5f)));
      return w;
    };
    const Vec3 wo = randomDirection(), wi = randomDirection();
    for (TransportMode mode : kModes) {
      const BsdfEval e = bsdf.eval(wo, wi, mode);
      ASSERT_TRUE(isValidContribution(e.f));
      ASSERT_TRUE(std::isfinite(e.pdfFwdW) && e.pdfFwdW >= 0.f);
      ASSERT_TRUE(std::isfinite(e.pdfRevW) && e.pdfRevW >= 0.f);
      const std::optional<BsdfSample> s = bsdf.sample(wo, rng.next2D(), rng.next1D(), mode);
      if (!s) continue;
      ASSERT_TRUE(isValidContribution(s->f));
      ASSERT_TRUE(std::isfinite(s->pdfFwdW) && s->pdfFwdW > 0.f);
      ASSERT_TRUE(std::isfinite(s->pdfRevW) && s->pdfRevW >= 0.f);
      ASSERT_TRUE(std::isfinite(s->wi.x) && std::isfinite(s->wi.y) && std::isfinite(s->wi.z));
    }
  }
}
