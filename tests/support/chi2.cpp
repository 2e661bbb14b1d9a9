// Chi-square test of direction samplers: histogram, adaptive pdf integration, pooling, p-value.
#include "tests/support/chi2.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <queue>
#include <utility>
#include <vector>

namespace pathlab::test {

namespace {

constexpr double kTwoPi = 6.283185307179586476925;

// Regularized lower incomplete gamma by its series, valid for x < a + 1 (Numerical Recipes 6.2).
double gammaPSeries(double a, double x) {
  double sum = 1.0 / a, term = sum, ap = a;
  for (int n = 0; n < 10000; ++n) {
    ap += 1.0;
    term *= x / ap;
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Regularized upper incomplete gamma by Lentz's continued fraction, valid for x >= a + 1.
double gammaQContinuedFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

// 4-point Gauss-Legendre on [-1, 1].
constexpr double kGlNode[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                               0.8611363115940526};
constexpr double kGlWeight[4] = {0.3478548513745140, 0.6521451548625461, 0.6521451548625461,
                                 0.3478548513745140};

Vec3 directionFromZPhi(double z, double phi) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)),
              static_cast<float>(z));
}

// Integrals of the pdf over a (z, phi) rectangle; dOmega = dz dphi, so no Jacobian.
struct RectIntegrator {
  const std::function<double(const Vec3&)>& pdf;
  long long evaluations = 0;

  double value(double z, double phi) {
    ++evaluations;
    const double v = pdf(directionFromZPhi(z, phi));
    return std::isfinite(v) ? v : 0.0;
  }
  // Tensor 4-point Gauss-Legendre: the estimate.
  double operator()(double z0, double z1, double p0, double p1) {
    const double hz = 0.5 * (z1 - z0), hp = 0.5 * (p1 - p0);
    const double cz = 0.5 * (z0 + z1), cp = 0.5 * (p0 + p1);
    double sum = 0.0;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j)
        sum += kGlWeight[i] * kGlWeight[j] * value(cz + hz * kGlNode[i], cp + hp * kGlNode[j]);
    }
    return sum * hz * hp;
  }
  // Tensor Simpson: a closed rule whose nodes include the edges, so a jump near an edge, which
  // every open rule of the region and its halves would miss, shows up as a disagreement.
  double closed(double z0, double z1, double p0, double p1) {
    constexpr double w[3] = {1.0, 4.0, 1.0};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j)
        sum += w[i] * w[j] * value(z0 + 0.5 * i * (z1 - z0), p0 + 0.5 * j * (p1 - p0));
    }
    return sum * (z1 - z0) * (p1 - p0) / 36.0;
  }
};

// A rectangle of the adaptive integration with its own estimate and those of its halves along
// z and along phi; the disagreement is the error estimate and decides the split axis.
struct Region {
  int cell;
  int depth;
  double z0, z1, p0, p1;
  double whole;
  double zHalves[2], pHalves[2];
  double error, tolerance;

  double zError() const { return std::abs(zHalves[0] + zHalves[1] - whole); }
  double pError() const { return std::abs(pHalves[0] + pHalves[1] - whole); }
  double best() const {
    return zError() >= pError() ? zHalves[0] + zHalves[1] : pHalves[0] + pHalves[1];
  }
  bool operator<(const Region& o) const { return error / tolerance < o.error / o.tolerance; }
};

// The sampled (z, phi) positions, per cell and sorted by z. A quadrature rule can miss a small
// support (a narrow cone, a sharp peak) entirely; a region that holds a sample but whose every
// evaluation is zero is refined until the rule sees the support or the depth limit is reached.
struct Witnesses {
  std::vector<std::array<float, 2>> points;  // grouped by cell, sorted by z within a cell
  std::vector<size_t> offsets;               // cell c owns points[offsets[c], offsets[c + 1])

  Witnesses(std::vector<std::pair<int, std::array<float, 2>>> samples, int cellCount) {
    std::sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first < b.first : a.second[0] < b.second[0];
    });
    offsets.assign(cellCount + 1, 0);
    points.reserve(samples.size());
    for (const auto& [cell, point] : samples) {
      ++offsets[cell + 1];
      points.push_back(point);
    }
    for (int c = 0; c < cellCount; ++c) offsets[c + 1] += offsets[c];
  }
  bool inside(const Region& r) const {
    const auto begin = points.begin() + offsets[r.cell], end = points.begin() + offsets[r.cell + 1];
    auto it = std::lower_bound(begin, end, static_cast<float>(r.z0),
                               [](const std::array<float, 2>& p, float z) { return p[0] < z; });
    for (; it != end && (*it)[0] <= static_cast<float>(r.z1); ++it) {
      if ((*it)[1] >= static_cast<float>(r.p0) && (*it)[1] <= static_cast<float>(r.p1)) return true;
    }
    return false;
  }
};

struct AdaptiveCubature {
  RectIntegrator integrate;
  const Witnesses& witnesses;
  double absTolerance;
  double relTolerance;
  double cellDz, cellDphi;
  static constexpr int kMaxDepth = 60;

  Region make(int cell, int depth, double z0, double z1, double p0, double p1, double whole) {
    Region r{cell, depth, z0, z1, p0, p1, whole, {}, {}, 0, 0};
    const double zm = 0.5 * (z0 + z1), pm = 0.5 * (p0 + p1);
    r.zHalves[0] = integrate(z0, zm, p0, p1);
    r.zHalves[1] = integrate(zm, z1, p0, p1);
    r.pHalves[0] = integrate(z0, z1, p0, pm);
    r.pHalves[1] = integrate(z0, z1, pm, p1);
    r.error = std::max({r.zError(), r.pError(),
                        std::abs(integrate.closed(z0, z1, p0, p1) - r.best())});
    r.tolerance = std::max(absTolerance, relTolerance * std::abs(r.best()));
    if (depth >= kMaxDepth) {
      r.error = 0.0;
    } else if (whole == 0.0 && r.zHalves[0] == 0.0 && r.zHalves[1] == 0.0 &&
               r.pHalves[0] == 0.0 && r.pHalves[1] == 0.0 && witnesses.inside(r)) {
      r.error = 1e30 * r.tolerance * std::exp2(-depth);
    }
    return r;
  }

  // Splits along the axis where the halves disagree more with the whole; on a tie (nothing
  // resolved yet), along the side that is longer relative to the cell.
  void split(const Region& r, std::priority_queue<Region>& regions) {
    const double ez = r.zError(), ep = r.pError();
    const bool splitZ =
        ez != ep ? ez > ep : (r.z1 - r.z0) / cellDz >= (r.p1 - r.p0) / cellDphi;
    if (splitZ) {
      const double zm = 0.5 * (r.z0 + r.z1);
      regions.push(make(r.cell, r.depth + 1, r.z0, zm, r.p0, r.p1, r.zHalves[0]));
      regions.push(make(r.cell, r.depth + 1, zm, r.z1, r.p0, r.p1, r.zHalves[1]));
    } else {
      const double pm = 0.5 * (r.p0 + r.p1);
      regions.push(make(r.cell, r.depth + 1, r.z0, r.z1, r.p0, pm, r.pHalves[0]));
      regions.push(make(r.cell, r.depth + 1, r.z0, r.z1, pm, r.p1, r.pHalves[1]));
    }
  }
};

struct CellStat {
  int index;  // -1 = the rejected bin
  double observed, expected;
};

std::string describeCell(int index, int phiBins) {
  char buf[64];
  if (index < 0) return "rejected";
  std::snprintf(buf, sizeof buf, "(theta %d, phi %d)", index / phiBins, index % phiBins);
  return buf;
}

}  // namespace

double regularizedGammaQ(double a, double x) {
  if (x <= 0.0) return 1.0;
  if (x < a + 1.0) return std::clamp(1.0 - gammaPSeries(a, x), 0.0, 1.0);
  return std::clamp(gammaQContinuedFraction(a, x), 0.0, 1.0);
}

double sidakSignificance(double familySignificance, int testCount) {
  return 1.0 - std::pow(1.0 - familySignificance, 1.0 / std::max(testCount, 1));
}

Chi2Result chi2SphereTest(const std::function<std::optional<Vec3>(Pcg32&)>& sample,
                          const std::function<double(const Vec3&)>& pdf, int thetaBins,
                          int phiBins, int sampleCount, uint64_t seed, double significance) {
  Chi2Result result;
  if (thetaBins < 1 || phiBins < 1 || sampleCount < 1) {
    result.message = "chi2SphereTest needs at least one bin and one sample";
    return result;
  }
  const int cellCount = thetaBins * phiBins;
  const double n = sampleCount;
  char buf[256];

  // Histogram. Theta row 0 is around +z (cosTheta near 1); cells are equal in z and phi, hence
  // in solid angle.
  std::vector<double> observed(cellCount + 1, 0.0);
  std::vector<std::pair<int, std::array<float, 2>>> positions;
  positions.reserve(sampleCount);
  Pcg32 rng(mixBits(seed), mixBits(seed ^ 0x5bd1e995ULL));
  for (int k = 0; k < sampleCount; ++k) {
    const std::optional<Vec3> w = sample(rng);
    if (!w) {
      observed[cellCount] += 1.0;
      continue;
    }
    const double length = std::sqrt(double(w->x) * w->x + double(w->y) * w->y + double(w->z) * w->z);
    if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-3) {
      std::snprintf(buf, sizeof buf, "sample %d is not a unit direction: (%g, %g, %g)", k, w->x,
                    w->y, w->z);
      result.message = buf;
      return result;
    }
    const double z = std::clamp(double(w->z) / length, -1.0, 1.0);
    double phi = std::atan2(double(w->y), double(w->x));
    if (phi < 0.0) phi += kTwoPi;
    const int ti = std::clamp(static_cast<int>((1.0 - z) * 0.5 * thetaBins), 0, thetaBins - 1);
    const int pi = std::clamp(static_cast<int>(phi / kTwoPi * phiBins), 0, phiBins - 1);
    observed[ti * phiBins + pi] += 1.0;
    positions.push_back({ti * phiBins + pi, {static_cast<float>(z), static_cast<float>(phi)}});
  }

  // Expected probabilities: refine the region whose error most exceeds its tolerance until all
  // are within tolerance or the evaluation budget is spent. The absolute tolerance keeps each
  // region's expected-count error far below one sample.
  const Witnesses witnesses(std::move(positions), cellCount);
  const double dz = 2.0 / thetaBins, dphi = kTwoPi / phiBins;
  AdaptiveCubature cubature{RectIntegrator{pdf}, witnesses, 0.01 / n, 1e-6, dz, dphi};
  constexpr long long kEvaluationBudget = 3'000'000;
  std::priority_queue<Region> regions;
  for (int ti = 0; ti < thetaBins; ++ti) {
    for (int pi = 0; pi < phiBins; ++pi) {
      const double z1 = 1.0 - ti * dz, z0 = 1.0 - (ti + 1) * dz;
      const double p0 = pi * dphi, p1 = (pi + 1) * dphi;
      const double whole = cubature.integrate(z0, z1, p0, p1);
      regions.push(cubature.make(ti * phiBins + pi, 0, z0, z1, p0, p1, whole));
    }
  }
  bool budgetExhausted = false;
  while (!regions.empty() && regions.top().error > regions.top().tolerance) {
    if (cubature.integrate.evaluations > kEvaluationBudget) {
      budgetExhausted = true;
      break;
    }
    const Region r = regions.top();
    regions.pop();
    cubature.split(r, regions);
  }
  std::vector<double> probability(cellCount, 0.0);
  double integrationError = 0.0;
  while (!regions.empty()) {
    probability[regions.top().cell] += regions.top().best();
    integrationError += std::min(regions.top().error, std::abs(regions.top().best()));
    regions.pop();
  }
  double mass = 0.0;
  for (double& p : probability) {
    p = std::max(p, 0.0);
    mass += p;
  }

  std::vector<CellStat> cells;
  cells.reserve(cellCount + 1);
  for (int c = 0; c < cellCount; ++c) cells.push_back({c, observed[c], n * probability[c]});
  cells.push_back({-1, observed[cellCount], std::max(0.0, n * (1.0 - mass))});

  const double accepted = (n - observed[cellCount]) / n;
  std::snprintf(buf, sizeof buf,
                "accepted fraction %.6f vs pdf integral %.6f (integration error <= %.2g%s); ",
                accepted, mass, integrationError, budgetExhausted ? ", budget exhausted" : "");
  result.message = buf;

  // Pool cells with expected count < 5, smallest first (Mitsuba chi2.py).
  std::sort(cells.begin(), cells.end(),
            [](const CellStat& a, const CellStat& b) { return a.expected < b.expected; });
  double chi2 = 0.0, pooledObserved = 0.0, pooledExpected = 0.0;
  int dof = 0;
  std::vector<std::pair<double, CellStat>> contributions;
  for (const CellStat& c : cells) {
    if (c.expected == 0.0 && c.observed > 0.0) {
      std::snprintf(buf, sizeof buf, "%g samples in cell %s whose expected count is 0",
                    c.observed, describeCell(c.index, phiBins).c_str());
      result.message += buf;
      return result;
    }
    if (c.expected < 5.0) {
      pooledObserved += c.observed;
      pooledExpected += c.expected;
      if (pooledExpected > 5.0) {
        const double d = pooledObserved - pooledExpected;
        chi2 += d * d / pooledExpected;
        contributions.push_back({d * d / pooledExpected, CellStat{-2, pooledObserved, pooledExpected}});
        ++dof;
        pooledObserved = pooledExpected = 0.0;
      }
    } else {
      const double term = (c.observed - c.expected) * (c.observed - c.expected) / c.expected;
      chi2 += term;
      contributions.push_back({term, c});
      ++dof;
    }
  }
  // A pool still below 5 at the end is dropped, as in chi2.py; its counts are tiny either way.
  dof -= 1;
  if (dof < 1) {
    result.message += "fewer than 1 degree of freedom: the sampler covers too few cells";
    return result;
  }
  result.pValue = regularizedGammaQ(0.5 * dof, 0.5 * chi2);
  result.passed = result.pValue > significance;
  std::snprintf(buf, sizeof buf, "chi2 = %.2f, dof = %d, p = %.3g (significance %.3g)", chi2, dof,
                result.pValue, significance);
  result.message += buf;
  if (!result.passed) {
    std::sort(contributions.begin(), contributions.end(),
              [](const auto& a, const auto& b) { return a.first > b.first; });
    result.message += "; worst cells:";
    for (size_t k = 0; k < std::min<size_t>(6, contributions.size()); ++k) {
      const CellStat& c = contributions[k].second;
      std::snprintf(buf, sizeof buf, " %s obs %.0f exp %.1f (+%.1f);",
                    c.index == -2 ? "pooled" : describeCell(c.index, phiBins).c_str(), c.observed,
                    c.expected, contributions[k].first);
      result.message += buf;
    }
  }
  return result;
}

}  // namespace pathlab::test
