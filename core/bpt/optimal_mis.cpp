// OptimalMis: the regions' sums, their systems and the corrections (optimal_mis.h).
#include "core/bpt/optimal_mis.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/bpt/light_paths.h"

namespace pathlab {

namespace {

// Doubles of one length's sums (M, v, N) and floats of its beta, m = k + 1 techniques.
size_t sumsOfLength(int k) {
  const size_t m = static_cast<size_t>(k) + 1;
  return m * m + 3 * m + m + 3;  // M, v, N, Q
}
size_t betaOfLength(int k) { return 3 * (static_cast<size_t>(k) + 1); }

}  // namespace

bool solveOptimalMis(int m, const double* M, const double* d, const double* v, double* beta) {
  const size_t n = static_cast<size_t>(m);
  std::fill(beta, beta + 3 * n, 0.0);
  if (m <= 0) return true;
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(d[i])) return false;
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(v[static_cast<size_t>(c) * n + i])) return false;
    for (size_t j = i; j < n; ++j)
      if (!std::isfinite(M[i * n + j])) return false;
  }
  // A = M + diag(d), with the rows that saw nothing (A_ii = 0: no sample of the technique drew a
  // contribution, nor was it sampled) pinned to beta_i = 0. A tiny ridge, relative to the largest
  // diagonal, keeps the factorisation stable where two techniques' weights are nearly collinear.
  thread_local std::vector<double> A, L;
  A.assign(n * n, 0.0);
  double largest = 0.0;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i; j < n; ++j) A[i * n + j] = A[j * n + i] = M[i * n + j] + (i == j ? d[i] : 0.0);
  for (size_t i = 0; i < n; ++i) largest = std::max(largest, A[i * n + i]);
  if (!(largest > 0.0) || !std::isfinite(largest)) return largest == 0.0;
  std::vector<uint8_t> pinned(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (A[i * n + i] > 0.0) {
      A[i * n + i] += 1e-12 * largest;
      continue;
    }
    pinned[i] = 1;
    for (size_t j = 0; j < n; ++j) A[i * n + j] = A[j * n + i] = 0.0;
    A[i * n + i] = 1.0;
  }
  // Cholesky A = L L^T.
  L.assign(n * n, 0.0);
  for (size_t j = 0; j < n; ++j) {
    double diag = A[j * n + j];
    for (size_t k = 0; k < j; ++k) diag -= L[j * n + k] * L[j * n + k];
    if (!(diag > 0.0) || !std::isfinite(diag)) return false;
    const double ljj = std::sqrt(diag);
    L[j * n + j] = ljj;
    for (size_t i = j + 1; i < n; ++i) {
      double x = A[i * n + j];
      for (size_t k = 0; k < j; ++k) x -= L[i * n + k] * L[j * n + k];
      L[i * n + j] = x / ljj;
    }
  }
  for (int c = 0; c < 3; ++c) {
    double* x = beta + static_cast<size_t>(c) * n;
    for (size_t i = 0; i < n; ++i) {  // L y = v
      double y = pinned[i] ? 0.0 : v[static_cast<size_t>(c) * n + i];
      for (size_t k = 0; k < i; ++k) y -= L[i * n + k] * x[k];
      x[i] = y / L[i * n + i];
    }
    for (size_t i = n; i-- > 0;) {  // L^T beta = y
      double y = x[i];
      for (size_t k = i + 1; k < n; ++k) y -= L[k * n + i] * x[k];
      x[i] = y / L[i * n + i];
    }
    for (size_t i = 0; i < n; ++i)
      if (!std::isfinite(x[i])) {
        std::fill(beta, beta + 3 * n, 0.0);
        return false;
      }
  }
  return true;
}

uint64_t OptimalMis::bytesFor(int width, int height, uint64_t regions, int maxLength) {
  uint64_t perRegion = 0;
  for (int k = 1; k <= maxLength; ++k) perRegion += sumsOfLength(k) * sizeof(double) + betaOfLength(k) * sizeof(float);
  const uint64_t pixels = static_cast<uint64_t>(width) * static_cast<uint64_t>(height);
  return regions * perRegion + pixels * (sizeof(int32_t) + sizeof(DVec3));
}

OptimalMis::OptimalMis(int width, int height, std::vector<int32_t> regionOfPixel, int regions, int maxLength,
                       float lightPaths, double splatScale)
    : width_(width),
      height_(height),
      maxLength_(maxLength),
      lightPaths_(lightPaths),
      splatScale_(splatScale),
      regions_(regions),
      regionOfPixel_(std::move(regionOfPixel)) {
  regionPixels_.assign(static_cast<size_t>(regions_), 0.0);
  for (const int32_t r : regionOfPixel_)
    if (r >= 0) regionPixels_[static_cast<size_t>(r)] += 1.0;
  blocks_.resize(static_cast<size_t>(maxLength_) + 1);
  for (int k = 1; k <= maxLength_; ++k) {
    blocks_[static_cast<size_t>(k)] = Block{sumsPerRegion_, betaPerRegion_};
    sumsPerRegion_ += sumsOfLength(k);
    betaPerRegion_ += betaOfLength(k);
  }
  sums_.assign(static_cast<size_t>(regions_) * sumsPerRegion_, 0.0);
  beta_.assign(static_cast<size_t>(regions_) * betaPerRegion_, 0.f);
  splatCorrections_.assign(static_cast<size_t>(width_) * static_cast<size_t>(height_), DVec3(0.0));
}

int OptimalMis::regionOf(Vec2 pRaster) const {
  if (!(pRaster.x >= 0.f && pRaster.y >= 0.f)) return -1;
  const int x = static_cast<int>(pRaster.x), y = static_cast<int>(pRaster.y);
  if (x >= width_ || y >= height_) return -1;
  return regionOfPixel_[static_cast<size_t>(y) * static_cast<size_t>(width_) + static_cast<size_t>(x)];
}

void OptimalMis::learnFrom(int region, int s, int n, const Spectrum& C, const double* w) {
  const int k = n - 1;
  if (region < 0 || k < 1 || k > maxLength_) return;
  const size_t m = static_cast<size_t>(n);
  double* M = sumsOf(region, k);
  double* v = M + m * m;
  double* N = v + 3 * m;
  // M_ij = sum w_i w_j (the upper triangle, j >= i: solveOptimalMis reads no other), v_i = sum C w_i,
  // N_s = count.
  for (size_t i = 0; i < m; ++i) {
    const double wi = w[i];
    if (wi == 0.0) continue;
    for (size_t j = i; j < m; ++j) M[i * m + j] += wi * w[j];
    for (int c = 0; c < 3; ++c) v[static_cast<size_t>(c) * m + i] += static_cast<double>(C[c]) * wi;
  }
  N[static_cast<size_t>(s)] += 1.0;
  double* Q = N + m;
  for (int c = 0; c < 3; ++c) Q[c] += static_cast<double>(C[c]) * static_cast<double>(C[c]);
}

Spectrum OptimalMis::correction(int region, int s, int n, const double* w) const {
  const int k = n - 1;
  if (!active_ || region < 0 || k < 1 || k > maxLength_) return Spectrum(0.f);
  const float* b = betaOf(region, k);
  const size_t m = static_cast<size_t>(n);
  Spectrum out(0.f);
  for (int c = 0; c < 3; ++c) {
    const float* bc = b + static_cast<size_t>(c) * m;
    double x = bc[s];
    for (size_t i = 0; i < m; ++i) x -= static_cast<double>(bc[i]) * w[i];
    out[c] = static_cast<float>(x);
  }
  return out;
}

Spectrum OptimalMis::beta(int region, int s, int n) const {
  const int k = n - 1;
  if (!active_ || region < 0 || region >= regions_ || k < 1 || k > maxLength_ || s < 0 || s >= n) return Spectrum(0.f);
  const float* b = betaOf(region, k);
  const size_t m = static_cast<size_t>(n);
  return Spectrum(b[s], b[m + static_cast<size_t>(s)], b[2 * m + static_cast<size_t>(s)]);
}

Spectrum OptimalMis::addCamera(int s, int n, Vec2 pRaster, const Spectrum& C, const double* w, bool learn,
                               float roulette) {
  const int region = regionOf(pRaster);
  if (region < 0) return Spectrum(0.f);
  if (learn) learnFrom(region, s, n, C, w);
  return correction(region, s, n, w) * roulette;
}

void OptimalMis::addSplat(int s, int n, Vec2 pRaster, const Spectrum& splat, const double* w, Splats& splats,
                          float roulette) const {
  const int region = regionOf(pRaster);
  if (region < 0 || n - 1 > maxLength_) return;
  splats.entries.push_back(
      Splats::Entry{pixelOf(pRaster), region, s, n, splat * static_cast<float>(splatScale_), roulette, splats.weights.size()});
  splats.weights.insert(splats.weights.end(), w, w + n);
}

void OptimalMis::addSplats(Splats& splats, bool learn) {
  for (Splats::Entry e : splats.entries) {
    const double* w = splats.weights.data() + e.weightsAt;
    splatCorrections_[e.pixel] += DVec3(correction(e.region, e.s, e.n, w) * e.roulette);
    if (!learn) continue;
    e.weightsAt = passSplats_.weights.size();
    passSplats_.entries.push_back(e);
    passSplats_.weights.insert(passSplats_.weights.end(), w, w + e.n);
  }
  splats.clear();
}

void OptimalMis::finishPass(bool learnt) {
  // The pass's splats into the sums, in the work items' order (after its camera contributions).
  for (const Splats::Entry& e : passSplats_.entries)
    learnFrom(e.region, e.s, e.n, e.C, passSplats_.weights.data() + e.weightsAt);
  passSplats_.clear();
  ++passes_;
  if (learnt) ++learntPasses_;
  if (!learnt || !optimalMisSolvesAfter(learntPasses_)) return;
  active_ = true;
  const double passes = static_cast<double>(learntPasses_);
  const double pixels = static_cast<double>(width_) * static_cast<double>(height_);
  tbb::parallel_for(0, regions_, [&](int region) {
    thread_local std::vector<double> a, betaD;
    for (int k = 1; k <= maxLength_; ++k) {
      const int m = k + 1;
      const size_t mm = static_cast<size_t>(m);
      const double* M = sumsOf(region, k);
      const double* v = M + mm * mm;
      const double* N = v + 3 * mm;
      bool any = false;  // a length nothing contributed to keeps beta = 0 without a solve
      for (size_t i = 0; i < mm && !any; ++i) any = N[i] > 0.0;
      if (!any) continue;
      // a_s - N_s: technique s' = s of length k drew a_s samples aimed at this region over the
      // passes (optimal_mis.h), of which N_s contributed.
      a.assign(mm, 0.0);
      for (int s = 0; s < m; ++s) {
        const int t = m - s;
        const double perPass = t == 1 ? pixels * static_cast<double>(lightPaths_)
                                      : regionPixels_[static_cast<size_t>(region)] *
                                            (usesLightSubpath(s, t) ? static_cast<double>(lightPaths_) : 1.0);
        a[static_cast<size_t>(s)] = std::max(perPass * passes - N[s], 0.0);
      }
      betaD.assign(3 * mm, 0.0);
      solveOptimalMis(m, M, a.data(), v, betaD.data());
      // Shrunk toward zero by the share of its fit that noise alone would give (positive-part
      // James-Stein): beta^T v is the sum of squares the fit explains; m sigma^2 is what m
      // coefficients fitted to pure noise explain in expectation, sigma^2 the residual's mean square
      // per contribution. A pixel whose sums hold a rare large contribution (a caustic's firefly) would
      // otherwise correct every later sample by that firefly's share, adding the variance it was to
      // remove; one whose techniques' shares follow the contributions keeps nearly all of its beta.
      const double* Q = N + mm;
      double contributions = 0.0;
      int fitted = 0;
      for (size_t i = 0; i < mm; ++i) {
        contributions += N[i];
        fitted += N[i] > 0.0 ? 1 : 0;
      }
      for (size_t c = 0; c < 3; ++c) {
        double explained = 0.0;
        for (size_t i = 0; i < mm; ++i) explained += betaD[c * mm + i] * v[c * mm + i];
        const double sigma2 = std::max(Q[c] - explained, 0.0) / std::max(contributions - fitted, 1.0);
        const double shrink =
            explained > 0.0 ? std::max(0.0, 1.0 - kOptimalMisShrink * fitted * sigma2 / explained) : 0.0;
        for (size_t i = 0; i < mm; ++i) betaD[c * mm + i] *= shrink;
      }
      float* b = beta_.data() + static_cast<size_t>(region) * betaPerRegion_ + blocks_[static_cast<size_t>(k)].beta;
      for (size_t i = 0; i < 3 * mm; ++i) b[i] = static_cast<float>(betaD[i]);
    }
  });
}

}  // namespace pathlab
