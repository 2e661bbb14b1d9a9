// Optimal MIS (Kondapaneni, Vévoda, Grittmann, Skřivan, Slusallek and Křivánek 2019, "Optimal
// multiple importance sampling", SIGGRAPH): the weights of least variance among all that sum to one
// on every path. For techniques i with n_i samples and densities p_i, the Lagrangian of
//     V(w) = sum_i (1 / n_i) [ int w_i^2 f^2 / p_i - (int w_i f)^2 ]   subject to sum_i w_i = 1
// gives (the paper's eq. 11)
//     w_i = alpha_i p_i / f + (n_i p_i / sum_j n_j p_j) (1 - sum_k alpha_k p_k / f),
// the balance heuristic plus a correction. A sample of technique i then contributes
//     w_i f / (n_i p_i) = C + beta_i - sum_k beta_k w^b_k,        beta_i = alpha_i / n_i,
// with C = f / sum_j n_j p_j the balance heuristic's contribution (the same whichever technique
// sampled the path) and w^b_k the balance weights of the path's techniques: the balance estimate
// with a control variate. The estimate is unbiased for any beta fixed before the samples are drawn:
// summed over the nonzero samples, E[beta_i 1{f != 0}] and E[sum_k beta_k w^b_k] are both
// sum_k beta_k n_k int_{f != 0} p_k. That is why only contributing paths carry a correction.
//
// The consistency condition alpha_i = int w_i f, taken over the paths that contribute (where the
// densities integrate to c_i = P(technique i contributes) < 1 rather than 1 as in the paper),
// becomes, per technique i,
//     sum_k A_ik n_k beta_k + (1 - c_i) beta_i = b_i,
//     A_ik = int p_i p_k / sum_j n_j p_j,   b_i = int f p_i / sum_j n_j p_j.
// Times n_i and the passes P, every term is a sum over the contributions the passes drew (the
// balance estimate of int g is sum g / sum_j n_j p_j):
//     (M + diag(a - N)) beta = v,   M_ik = sum w^b_i w^b_k,   v_i = sum C w^b_i,
// N_i the contributions of technique i and a_i the samples it drew (a_i - N_i those that gave
// nothing): a technique whose samples rarely contribute keeps beta_i near 0, since adding a
// constant to rare events is noise. With c_i = 1 it is the paper's A alpha = b; with one technique
// beta = the mean contribution and the correction vanishes. One system per channel (v), per path
// length and per region of the image (a pixel, or a few where the sums would take too much memory:
// cells cut along the work items as variance-aware MIS's), solved from all the passes so far
// (optimalMisSolvesAfter); the next passes use it (the paper's progressive form). Before
// kOptimalMisPilotPasses passes beta is zero: the balance heuristic. Regions of one pixel: beta fitted
// over several pixels of unlike brightness corrects the dark ones by the bright ones' scale, which
// measured worse than the balance heuristic there (veach-mis's dim floor beside its lamps). Each
// solution is shrunk toward zero by the share of its fit that noise alone would explain
// (kOptimalMisShrink): beta from a pixel's few samples, a heavy-tailed one above all, is not the
// optimum, and a poor estimate of it adds variance instead of removing it. Any beta fixed before
// the pass keeps the estimate unbiased, shrunk or not.
//
// Russian roulette, delta lobes and media. The densities of the weights leave out roulette's
// continuation probabilities (as pbrt's BDPT does) and a delta vertex's lobe choice (its densities
// count one), so technique i delivers a path with density p_i Q_i, Q_i the product of those
// probabilities over its prefixes' decisions, and weighs f / (p_i Q_i). Added as is, the correction's two terms
// would have the expectations sum_k beta_k n_k int p_k Q_k and sum_k beta_k n_k int p_k sum_i w_i Q_i,
// unequal where the techniques' prefixes met different roulettes; scaled by c(x) / Q_i, c any
// function of the path alone, both are sum_k beta_k n_k int p_k c again (the correction then sums
// to zero path by path: sum_i n_i p_i c (beta_i - sum_k beta_k w_k) = 0). Here c is the product of
// the camera side's lobe choices at the delta vertices, so a sample's factor
// (TechniqueResult::omittedFactor) is its roulette's 1 / q times, for each delta vertex its light
// walk crossed, the camera side's choice probability over the light side's: one where the lobes
// are chosen alike both ways (a dielectric's Fresnel), rather than 1 / 0.04 for a glass reflection. Media's
// distance sampling and ratio tracking put factors of the same kind into the throughput that no
// sample knows exactly: --mis optimal is refused in scenes with media (validateSettingsForScene;
// a session given it there renders the balance heuristic). The learning sums ignore Q_i (beta is
// fitted to unscaled corrections): unbiased still, perhaps not the optimum on long paths.
//
// Samples per pass (a_i / P): a camera sample per pixel, so the region's pixels for the
// techniques with t >= 2, times F (--light-paths) for those that walk the light subpath; light
// tracing (t = 1) draws F x pixels light subpaths over the whole image, which land where they may.
// Every sum is deterministic (camera contributions by the work item that holds the region, splats
// in the items' order), so the same seed gives the same image at any thread count.
#pragma once

#include <cstdint>
#include <vector>

#include "core/math/types.h"

namespace pathlab {

inline constexpr int kOptimalMisPilotPasses = 4;
// The systems are solved after the learnt passes 4, 8, 16, then every 16th: a solve visits every
// region's every length, more than a pass's samples do at low lengths, and beta settles slowly.
inline constexpr bool optimalMisSolvesAfter(uint64_t learnt) {
  return learnt >= static_cast<uint64_t>(kOptimalMisPilotPasses) && (learnt % 16 == 0 || (learnt & (learnt - 1)) == 0);
}
// The shrinkage of each system's beta toward zero: by kOptimalMisShrink times the share of its fit
// that noise alone would explain (OptimalMis::finishPass). Measured on cornell-spheres, cornell-box,
// environment and smoke (128 px, 128-256 spp, two seeds): 0 let the caustics' fireflies make
// cornell-spheres' relative variance 1.7 times the balance heuristic's; 1 to 3 kept every one at or
// below it, the others' gains within 2 % of unshrunk.
inline constexpr double kOptimalMisShrink = 2.0;
// The regions' cells (pixels a side), doubled while the tables would pass kOptimalMisBytes.
inline constexpr int kOptimalMisCell = 1;
inline constexpr uint64_t kOptimalMisBytes = uint64_t{1} << 30;

// Solves (M + diag(d)) beta = v for m unknowns and three right-hand sides (Cholesky): M row-major
// m x m, symmetric positive semi-definite, read from its upper triangle (j >= i) only; d >= 0; v and beta channel-major
// (v[c * m + i]). A row with nothing on its diagonal gets beta_i = 0. Returns false (beta all zero) when the system is
// not positive definite after that (a NaN in the sums, say).
bool solveOptimalMis(int m, const double* M, const double* d, const double* v, double* beta);

class OptimalMis {
 public:
  // regionOfPixel: each pixel's region (variance_aware_regions.h: cells cut along the work items).
  // lightPaths: F, the light subpaths per camera sample; splatScale: a splat's value times this is
  // its contribution to its pixel per camera sample (pixels / light subpaths per pass).
  OptimalMis(int width, int height, std::vector<int32_t> regionOfPixel, int regions, int maxLength, float lightPaths,
             double splatScale);
  static uint64_t bytesFor(int width, int height, uint64_t regions, int maxLength);

  int regions() const { return regions_; }
  int regionOf(Vec2 pRaster) const;
  bool active() const { return active_; }
  uint64_t passes() const { return passes_; }

  // A contribution of connection (s, n - s) of a path of n vertices: C as the image received it (a
  // splat's value, for t = 1), w its path's balance weights by s' (n of them), where it lands.
  // A camera contribution (t >= 2) is learnt from at once (`learn`) and its correction, the beta of
  // the passes before, returned for the caller to add to its pixel. A splat is kept in `splats`
  // (the work item's); addSplats adds its correction to splatCorrections() and keeps it for
  // finishPass to learn from (not at once: the pixel's sums may be its own work item's, being
  // rendered by another thread).
  struct Splats {
    struct Entry {
      uint32_t pixel;
      int32_t region;
      int s, n;
      Spectrum C;
      float roulette;
      size_t weightsAt;
    };
    std::vector<Entry> entries;
    std::vector<double> weights;
    void clear() {
      entries.clear();
      weights.clear();
    }
  };
  // `roulette`: the sample's omitted factor (TechniqueResult::omittedFactor), which scales
  // its correction (the class comment says why).
  Spectrum addCamera(int s, int n, Vec2 pRaster, const Spectrum& C, const double* w, bool learn, float roulette = 1.f);
  void addSplat(int s, int n, Vec2 pRaster, const Spectrum& splat, const double* w, Splats& splats,
                float roulette = 1.f) const;
  void addSplats(Splats& splats, bool learn);  // then cleared
  // The splats' corrections of the pass, per pixel per camera sample (3 doubles a pixel), which the
  // session adds to the film once the pass's camera samples are in; then zeroed.
  std::vector<DVec3>& splatCorrections() { return splatCorrections_; }
  // The correction of a contribution of technique s' = s of a path of n vertices, in region r:
  // beta_s - sum_k beta_k w_k (zero before the pilot passes).
  Spectrum correction(int region, int s, int n, const double* w) const;
  // beta of technique s of length n - 1 in region r (the inspector; zero before the pilot passes).
  Spectrum beta(int region, int s, int n) const;

  // The end of a pass (`learnt`: its contributions are in the sums): on the solving passes
  // (optimalMisSolvesAfter) every region's systems solved anew.
  void finishPass(bool learnt);
  void discardPass() { passSplats_.clear(); }  // a cancelled pass's splats

 private:
  struct Block {  // offsets of one length's sums within a region's, and of its beta
    size_t sums = 0, beta = 0;
  };
  void learnFrom(int region, int s, int n, const Spectrum& C, const double* w);
  uint32_t pixelOf(Vec2 pRaster) const {
    return static_cast<uint32_t>(static_cast<int>(pRaster.y) * width_ + static_cast<int>(pRaster.x));
  }
  double* sumsOf(int region, int k) {
    return sums_.data() + static_cast<size_t>(region) * sumsPerRegion_ + blocks_[static_cast<size_t>(k)].sums;
  }
  const float* betaOf(int region, int k) const {
    return beta_.data() + static_cast<size_t>(region) * betaPerRegion_ + blocks_[static_cast<size_t>(k)].beta;
  }
  int width_, height_, maxLength_;
  float lightPaths_;
  double splatScale_;
  int regions_;
  std::vector<int32_t> regionOfPixel_;
  std::vector<double> regionPixels_;
  std::vector<Block> blocks_;  // by length k = n - 1 (m = k + 1 techniques): M (m x m), v (3m), N (m)
  size_t sumsPerRegion_ = 0, betaPerRegion_ = 0;
  std::vector<double> sums_;
  std::vector<float> beta_;
  std::vector<DVec3> splatCorrections_;
  Splats passSplats_;  // the pass's splats in the work items' order, learnt from by finishPass
  uint64_t passes_ = 0, learntPasses_ = 0;
  bool active_ = false;
};

}  // namespace pathlab
