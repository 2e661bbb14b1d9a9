// Chi-square goodness-of-fit test of a direction sampler against its own solid-angle density
// (after Mitsuba 3's chi2.py: spherical domain, cell pooling, Pearson's statistic).
#pragma once

#include "core/math/rng.h"

#include <functional>
#include <optional>
#include <string>

namespace pathlab::test {

struct Chi2Result {
  bool passed = false;
  double pValue = 0;
  std::string message;
};

// Draw `sampleCount` directions with `sample` (nullopt = sample rejected/absorbed), bin them on the
// sphere in (cosTheta, phi) with thetaBins x phiBins equal-solid-angle cells, integrate `pdf`
// (solid-angle density, possibly integrating to < 1) numerically over each cell for the expected
// counts, pool cells with expected count < 5 (Mitsuba chi2.py style), and run Pearson's chi-square
// test at `significance` (pass an already Šidák-corrected value if the caller runs many tests).
// Rejected samples go to one extra bin whose expected count is sampleCount * (1 - integral of
// pdf), so the accepted mass is tested too. The pdf is integrated adaptively (Gauss-Legendre
// cells refined where they disagree with their halves), so peaky and discontinuous densities are
// handled. Non-finite or non-unit sampled directions fail the test outright.
Chi2Result chi2SphereTest(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                          const std::function<double(const Vec3&)>& pdf,
                          int thetaBins, int phiBins, int sampleCount, uint64_t seed,
                          double significance = 0.01);

// Regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a); the chi-square
// survival function with k degrees of freedom is Q(k / 2, x / 2). Exposed for its own tests.
double regularizedGammaQ(double a, double x);

// Šidák correction: the per-test significance so that `testCount` independent tests together
// reject a correct sampler with probability `familySignificance`.
double sidakSignificance(double familySignificance, int testCount);

}  // namespace pathlab::test
