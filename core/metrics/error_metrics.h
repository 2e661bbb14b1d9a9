// Image error against a reference (RMSE, relative MSE, MAPE) and, without one, the two-buffer
// estimate of the error of a progressive mean from its even and odd passes.
#pragma once

#include "core/film/film.h"

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace pathlab {

// The ε of relative MSE: per-pixel squared error over (reference² + ε). It keeps black pixels from
// dominating (a pixel whose reference is 0 would otherwise weigh infinitely). 1e-2 is the value of
// Rousselle, Knaus and Zwicker 2011 ("Adaptive sampling and reconstruction using greedy error
// minimization"), reused by most later work on denoising and adaptive sampling.
inline constexpr double kRelMseEpsilon = 1e-2;
// The ε of MAPE (mean absolute percentage error): |x − r| / (|r| + ε), for the same reason.
inline constexpr double kMapeEpsilon = 1e-2;

// Every metric is a mean over all pixels and all three channels (as pbrt-v4's imgtool).
struct ErrorMetrics {
  double mse = 0.0;
  double rmse = 0.0;    // sqrt(mse)
  double relMse = 0.0;  // mean (x − r)² / (r² + kRelMseEpsilon)
  double mape = 0.0;    // mean |x − r| / (|r| + kMapeEpsilon)
};

// Which pixels an error is measured over (a region of interest: the caustic, a reflection), one
// value per pixel, row by row; empty: every pixel.
using PixelMask = std::vector<uint8_t>;

// Throws std::invalid_argument when the sizes differ. With a mask, the means are over the masked
// pixels' channels only.
ErrorMetrics errorMetrics(const Image& image, const Image& reference, const PixelMask& mask = {});

// The relative MSE of a progressive mean image against a reference, split into its variance and
// its squared bias (issue 32: merging is consistent, not unbiased; its error is both).
// Per value i (pixel and channel), with m the mean of n passes and r the reference,
//     E[(m_i - r_i)^2] = bias_i^2 + Var(m_i),
// and the two-buffer estimate v_i = (A_i - B_i)^2 mA mB / n^2 (EvenOddBuffers) is an unbiased
// estimate of Var(m_i) when the passes are independent and alike. So
//     variance = mean_i v_i / (r_i^2 + eps),   bias2 = relMse - variance,
// with relMse = mean_i (m_i - r_i)^2 / (r_i^2 + eps) as errorMetrics computes it: the two parts
// sum to relMse by construction, and bias2 is an unbiased estimate of the bias's share (of the
// reference's too: a reference of finite passes contributes its own variance here). It is signed:
// where the estimator is unbiased (bpt) it scatters around zero by about the variance part's own
// noise, and a value of the order of the variance part says nothing yet. With a progressive radius
// (alpha < 1) the passes are not alike (each merges within its own r_i), the even and odd halves
// differ by the bias of neighbouring radii, and v_i slightly overstates the variance; at alpha = 1
// the split is exact in expectation.
struct RelMseSplit {
  double relMse = 0.0, variance = 0.0, bias2 = 0.0;
};

// The variance part of the error of the mean image, estimated without a reference.
struct TwoBufferEstimate {
  double mse = 0.0;     // estimate of E[(mean − truth)²] without bias; compare with ErrorMetrics::mse
  // The same over (mean² + kRelMseEpsilon): the mean stands in for the reference. A pixel holding
  // a rare huge sample (a firefly) is normalised by its own inflated mean, so this underrates
  // error dominated by rare large samples; compare it with the reference's relMSE to see them.
  double relMse = 0.0;
};

// Passes are independent (every pass draws from streams keyed by the pass index), so the mean of
// the mA even passes (A) and of the mB odd passes (B) are independent unbiased estimates with
// per-pass variance σ². Then E[(A − B)²] = σ²(1/mA + 1/mB) = σ² n / (mA mB) with n = mA + mB,
// and the variance of the mean of all n passes is σ²/n, hence
//     Var(mean) ≈ (A − B)² · mA mB / n²,   which is (A − B)²/4 when mA = mB = n/2
// (the "two-buffer" estimate of the dual-buffer denoisers, e.g. Rousselle et al. 2012, "Adaptive
// rendering with non-local means filtering").
// Averaged over pixels it estimates the image's MSE without a reference (bias excluded).
class EvenOddBuffers {
 public:
  EvenOddBuffers(int width, int height);

  // One pass's own image (not a running mean): pass 0, 2, 4... go to A, 1, 3, 5... to B. Without
  // `passIndex`, passes are numbered in the order they are added.
  void addPass(const std::vector<double>& passRgb);
  void addPass(const std::vector<double>& passRgb, uint64_t passIndex);
  // The progressive mean after one more pass (what RenderSession::image() returns after pass n).
  // The pass's own image is n·mean_n − (n−1)·mean_{n−1}: the film's read-out is linear in its
  // sums with a constant number of light subpaths per pass (Film::readout), so this is exact up
  // to the float rounding of the read-out (about n · 6e-8 of the pixel value, far below the
  // noise of one pass for any pass count a run reaches).
  // `passIndex`: the pass's index in a render split over processes (PassSchedule), whose parity
  // picks the buffer, so that the processes' buffers add up to those of one process.
  void addRunningMean(const Image& mean);
  void addRunningMean(const Image& mean, uint64_t passIndex);

  uint64_t passes() const { return evenPasses_ + oddPasses_; }
  int width() const { return width_; }
  int height() const { return height_; }
  uint64_t evenPasses() const { return evenPasses_; }
  uint64_t oddPasses() const { return oddPasses_; }
  // The sums of the even and of the odd pass images (3 doubles a pixel): buffers that took
  // disjoint passes combine by adding these element by element, then addForeignPasses.
  std::array<std::span<double>, 2> sums() { return {std::span<double>(even_), std::span<double>(odd_)}; }
  std::array<std::span<const double>, 2> sums() const {
    return {std::span<const double>(even_), std::span<const double>(odd_)};
  }
  void addForeignPasses(uint64_t even, uint64_t odd) {
    evenPasses_ += even;
    oddPasses_ += odd;
  }
  // Needs at least one even and one odd pass; returns zeros before.
  TwoBufferEstimate estimate() const;
  // The two-buffer variance of the mean of value i (pixel, channel), (A_i - B_i)^2 mA mB / n^2;
  // 0 before one even and one odd pass.
  double varianceOfMean(size_t i) const;

 private:
  int width_, height_;
  std::vector<double> even_, odd_;  // sums of pass images
  std::vector<double> previousMean_;
  uint64_t evenPasses_ = 0, oddPasses_ = 0;
};

// RelMseSplit of the mean of `buffers`' passes: `mean` is that image (what errorMetrics compares);
// throws std::invalid_argument when the sizes differ.
RelMseSplit splitRelMse(const EvenOddBuffers& buffers, const Image& mean, const Image& reference,
                        const PixelMask& mask = {});

}  // namespace pathlab
