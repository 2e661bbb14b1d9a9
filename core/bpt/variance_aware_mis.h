// Variance-aware MIS (Grittmann, Georgiev, Slusallek and Křivánek 2019, "Variance-aware multiple
// importance sampling", SIGGRAPH Asia): the balance heuristic with each technique's sample count
// scaled by a factor that says how much better (or worse) its estimator is than its second moment
// alone, which is all the balance heuristic looks at:
//     w_i(x) = c_i n_i p_i(x) / sum_j c_j n_j p_j(x),   c_i = M_i / V_i,
// V_i the variance of technique i's own (unweighted) estimate of the pixel and M_i the second
// moment term of the same estimate, E[sum_s X_s^2] / N^2 over its N samples. For N independent,
// identically distributed samples M_i - V_i = I^2 / N, so c_i = 1 + I^2 / (N V_i), the paper's
// "1 + 1 / relative variance" (its eq. 9 with the robust "+1" of its implementation); where
// samples are stratified (one camera sample per pixel, against light tracing's splats that fall
// where they may) V_i is smaller and c_i larger, and where they are correlated (every camera
// sample merges with the same photons) V_i is larger and c_i < 1.
//
// The factors are estimated per region of the image (a few pixels; the paper's 16 x 16 blocks
// become 8 x 8 cells cut along the pass's work items) from the passes rendered so far: pass p's
// estimate of the region by technique i alone is A1 = sum X / N, its second-moment term
// A2 = sum X^2 / N^2 (X the unweighted contribution's luminance, N the region's pixels times the
// pass's samples per pixel; splats of t = 1 land in the region they hit and are normalised the
// same way, since the pass has as many light subpaths as camera samples). Over the passes,
// V = the sample variance of A1 and M = the mean of A2. A pass is weighted with the factors of
// the passes before it only, so each pass's weights are a partition of unity fixed before its
// samples are drawn and the estimate stays unbiased (the factors are a function of earlier,
// independent passes). Before kVarianceAwarePilotPasses passes every factor is 1 (the balance
// heuristic).
//
// Every sum is deterministic: the camera contributions of a region come from the one work item
// that holds it, in its samples' order; the splats are added by the render session in the work
// items' fixed order (RenderSession::renderPass). The same seed gives the same factors, so the same image, at any
// thread count.
#pragma once

#include "core/math/types.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// Passes with the balance heuristic before the factors apply: V from fewer passes is too noisy.
inline constexpr int kVarianceAwarePilotPasses = 4;
// The regions' cells (pixels a side), before cutting them along the work items; doubled while the
// tables would take more than kVarianceAwareBytes (a 1920 x 1080 image at length 10 takes 16-pixel
// cells).
inline constexpr int kVarianceAwareCell = 8;
inline constexpr uint64_t kVarianceAwareBytes = uint64_t{128} << 20;
// The passes the factors learn from: every one of the first kVarianceAwareEveryPassUpTo, then one
// in kVarianceAwareStride. A learning pass takes the kernel's recording route (every contribution's
// record) and weighs each connection before its shadow ray; the others render as the balance
// heuristic does but for the factors in the weights. Which passes learn is fixed in advance, so
// the factors still depend on earlier passes only.
inline constexpr uint64_t kVarianceAwareEveryPassUpTo = 32;
inline constexpr uint64_t kVarianceAwareStride = 8;
inline constexpr bool varianceAwareLearnsFrom(uint64_t pass) {
  return pass < kVarianceAwareEveryPassUpTo || pass % kVarianceAwareStride == 0;
}
// The factors are clamped to [1 / kVarianceAwareMaxFactor, kVarianceAwareMaxFactor]: a technique
// never vanishes from the weights, and a region whose estimate did not vary yet (V = 0) does not
// take every weight for one technique.
inline constexpr float kVarianceAwareMaxFactor = 1000.f;

class VarianceAwareFactors {
 public:
  // regionOfPixel: each pixel's region, 0 .. regions - 1, row-major (the render session's cells cut
  // along its work items, core/render/variance_aware_regions.h, so that each region lies in one
  // work item). Techniques up to maxLength, both families.
  VarianceAwareFactors(int width, int height, std::vector<int32_t> regionOfPixel, int regions, int maxLength);
  // Bytes the tables take for `regions` regions of a width x height image.
  static uint64_t bytesFor(int width, int height, uint64_t regions, int maxLength);

  int regions() const { return regions_; }
  int maxLength() const { return maxLength_; }
  // The region of the pixel pRaster falls in, or -1 off the film.
  int regionOf(Vec2 pRaster) const;
  // The factors of length k's techniques in the region, by Technique::slot() (connections C(s, .)
  // at s, merges M(s, .) at k - 1 + s): the row the MIS weights read (PathDensities::factors).
  // Null before the pilot passes (every factor 1); k within 1..maxLength.
  const float* factorsOfLength(int region, int k) const {
    if (!active_ || region < 0) return nullptr;
    return factors_.data() + static_cast<size_t>(region) * techniques_ + Technique::firstIndexOfLength(k);
  }
  float factor(int region, Technique x) const;
  // Learning passes whose sums are in (varianceAwareLearnsFrom).
  uint64_t passes() const { return passes_; }

  // One contributed technique result of the pass: its unweighted contribution's luminance, where
  // it lands. A camera contribution (t >= 2, merges) is added at once, by the thread of the work
  // item that holds its region. A splat is kept in `splats` (the work item's), which the session
  // adds in the items' order (addSplats).
  struct Splat {
    uint32_t slot;  // region * techniques + Technique::index()
    float luminance;
  };
  void add(Technique x, Vec2 pRaster, float luminance, std::vector<Splat>& splats);
  void addSplats(std::vector<Splat>& splats);  // then cleared
  // The end of a pass of `samplesPerPixel` camera samples a pixel: its regions' A1 and A2 into the
  // sums over passes, and every factor estimated anew.
  void finishPass(double samplesPerPixel);
  void discardPass();

  // The factor estimate of one region and technique from its sums (the formula above): exposed
  // for the tests.
  static float factorFromSums(double sumA1, double sumA1Squared, double sumA2, uint64_t passes);

 private:
  size_t slot(int region, Technique x) const { return static_cast<size_t>(region) * techniques_ + x.index(); }
  int width_, height_, maxLength_;
  size_t techniques_;  // Technique::countUpTo(maxLength): both families
  int regions_ = 0;
  std::vector<int32_t> regionOfPixel_;
  std::vector<double> regionPixels_;
  // This pass's sum X and sum X^2 by slot; over the passes, sum A1, sum A1^2 and sum A2.
  std::vector<double> passX_, passX2_, sumA1_, sumA1Squared_, sumA2_;
  std::vector<float> factors_;
  uint64_t passes_ = 0;
  bool active_ = false;
};

}  // namespace pathlab
