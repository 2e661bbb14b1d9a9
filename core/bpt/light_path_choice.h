// --light-paths auto: the number of light subpaths per camera sample chosen per image from the samples
// themselves (Grittmann, Yazici, Georgiev and Slusallek 2022, "Efficiency-aware multiple importance sampling
// for bidirectional rendering algorithms", sec. 4-5), among the candidates kLightPathCandidates, for the
// fixed-F sampling of light_paths.h.
//
// The variance of a candidate from the samples of the current one. Which paths the techniques sample does not
// depend on F: a candidate F_c changes only the MIS weights (the counts n_t: F for the techniques that walk a
// light subpath, light tracing and s >= 2, 1 for the others) and how often the light walk happens. Under the
// balance heuristic a technique's weight at F_c is its weight at the pass's F_n times r = sum_t n_t p_t /
// sum_t c_t p_t = 1 / (w_N + (F_c / F_n) w_L) (times F_c / F_n for the light-walk techniques), w_L the sum of
// the path's light-walk techniques' weights (lightWalkWeight, mis.h), w_N = 1 - w_L. So each camera sample's
// estimate of its pixel at F_c is known exactly from the same subpaths:
//     Y_c = A_c + (B_c / F_c) L_c,   A_c = sum over its camera-side contributions of X r,
//                                     L_c = sum over its light-walk contributions of X F_n (F_c / F_n) r,
// X the weighted contribution as rendered (1 / F_n included), B_c the walk (probability F_c). The pass
// observes L only where it walked (probability F_n, independent of the camera walk), so per sample
//     E[Y_c^2] ~ A_c^2 + [walked] (2 A_c L_c + L_c^2 / F_c) / F_n,   E[Y_c] ~ A_c + [walked] L_c / F_n,
// unbiased, covariances between the techniques of a sample (path reuse) included; F_c = F_n gives back Y^2
// and Y. The diagonal of Y_c^2 (each contribution's own square at F_c: (X r)^2 on the camera side,
// X^2 r^2 F_c / F_n for a light-walk one) is replaced by the balance form X^2 r: summed over the path's
// techniques both estimate sum_t E_c[X_t^2] = int f^2 / sum_t c_t p_t without bias, but the balance form
// reads it from whichever technique sampled the path, where the own squares wait for the technique that
// carries the path at F_c to sample it. Light tracing's splats come from other samples' independent light
// walks: each adds its X^2 r to the pixel it lands in (its variance: the square of its mean is
// O(1 / pixels)). The pixel's variance per camera sample at F_c is the mean of the first less the square
// of the mean of the second, plus the splats'.
//
// The choice. Per pixel p, the relative variance v_p(c) = V_p(c) / (I_p^2 + eps), I_p the image so far
// (luminance, a 3 x 3 box mean) and eps converge's relMSE epsilon (kRelativeErrorEpsilon): the error that
// `converge` measures. The cost of a camera sample is a + F b in rays: a the camera walk's rays,
// kCameraSampleCost, and the shadow rays of the techniques that do not walk a light subpath (s = 0,
// next-event estimation, E(1, t)), b the light walk's rays and the shadow rays of the techniques that do, per
// light subpath; a shadow ray counts kShadowRayCost of a walk's ray (measured: docs/benchmarks.md). Rays, not
// seconds, so that the same seed gives the same choice, and the same image, at any load and thread count. The
// chosen F minimises cost(c) * sum_p v_p(c), the relMSE of one sample a pixel times its cost (the paper
// weighs the second moment alone, leaving the covariances of path reuse out; on pathlab's scenes that
// misjudged bidir-lamp and veach-mis: docs/benchmarks.md); the brightest kOutlierFraction of the pixels are
// left out of each candidate's sum (one firefly of the pilot would otherwise decide).
//
// When. The first kLightPathPilotPasses passes render at F = 1 (or the F they are given) and learn; the
// choice is made after them and again after passes 8, 16, 32, ... from every learning pass so far (the
// pilot passes, then one in kLightPathsStride: pass 8 is the first of those, so the choice after 8 passes
// differs from the first only by the cost sums and the image). Each pass's F depends on earlier passes
// only, and each pass is unbiased at its own F (light_paths.h): the image stays unbiased.
//
// The sums take 2 floats a candidate a pixel (kLightPathChoiceBytesPerPixel). A cancelled pass leaves part of
// its sums: its session is discarded (RenderSession::renderPass).
//
// Every sum is deterministic: camera contributions come from the one work item that holds the pixel, in its
// samples' order; splats are added by the render session in the items' order.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/counters/counters.h"
#include "core/image/image.h"
#include "core/math/types.h"

namespace pathlab {

inline constexpr std::array<float, 9> kLightPathCandidates{1.f,     0.7071f, 0.5f,    0.3536f, 0.25f,
                                                           0.1768f, 0.125f,  0.0884f, 0.0625f};
inline constexpr int kLightPathPilotPasses = 4;
inline constexpr uint64_t kLightPathsEveryPassUpTo = kLightPathPilotPasses;
inline constexpr uint64_t kLightPathsStride = 8;
inline constexpr bool lightPathsLearnFrom(uint64_t pass) {
  return pass < kLightPathsEveryPassUpTo || pass % kLightPathsStride == 0;
}
// After pass `pass` (0-based) the choice is made anew: passes 4, 8, 16, 32, ... rendered.
inline constexpr bool lightPathsChooseAfter(uint64_t pass) {
  const uint64_t done = pass + 1;
  return done >= kLightPathPilotPasses && (done & (done - 1)) == 0;
}
inline constexpr double kShadowRayCost = 0.5;
// A camera sample's own work beside its rays (the camera ray's set-up, the film), in walk rays.
inline constexpr double kCameraSampleCost = 0.5;
inline constexpr double kOutlierFraction = 2e-5;
// converge's relMSE epsilon (core/metrics/error_metrics.h kRelMseEpsilon, which the kernel may not
// include; a test keeps them equal): the relative variance is the error `converge` measures.
inline constexpr double kRelativeErrorEpsilon = 1e-2;
inline constexpr uint64_t kLightPathChoiceBytesPerPixel = 2 * sizeof(float) * kLightPathCandidates.size();

// One candidate's estimates at a choice.
struct LightPathEstimate {
  float lightPaths = 1.f;
  double relativeVariance = 0.0;  // mean over the pixels of v_p(c): relMSE at one sample a pixel
  double cost = 0.0;              // rays a camera sample, a + F b
  double efficiency = 0.0;        // 1 / (relativeVariance * cost), relative to F = 1's
};
struct LightPathStatus {
  float lightPaths = 1.f;  // F of the next pass
  uint64_t passes = 0, choices = 0;
  std::vector<LightPathEstimate> estimates;
};

// The candidates' estimates as a table, a line each, the chosen one marked (render's summary, the
// viewer's tooltip).
std::string lightPathTable(const LightPathStatus& status, const std::string& indent = "");

class LightPathChoice {
 public:
  // `lightPaths`: F of the passes before the first choice.
  LightPathChoice(int width, int height, float lightPaths = 1.f);

  // F for the next pass.
  float lightPaths() const { return current_; }
  // Learning passes whose sums are in, and choices made.
  uint64_t passes() const { return passes_; }
  uint64_t choices() const { return choices_; }

  // A camera sample's own sums over its contributions (t >= 2), per candidate: A_c and L_c.
  struct SampleSums {
    std::array<double, kLightPathCandidates.size()> cameraSide{}, lightSide{};
    // Its contributions' own squares at F_c (the diagonal of Y_c^2), and their balance form X^2 r.
    std::array<double, kLightPathCandidates.size()> diagonal{}, balance{};
    bool walked = false;  // the sample walked a light subpath
    bool any = false;     // a contribution was added
  };
  // One weighted contribution of a learning pass: its luminance X as the image received it, where it lands,
  // the light-walk techniques' share of its balance weights (w_L) and whether it is one of them. A camera
  // contribution (t >= 2) goes into its sample's `sample` sums, added by addCameraSample; a splat (t = 1) is
  // kept in `splats` (the work item's), which the session adds in the items' order.
  struct Splat {
    uint32_t pixel;
    float x;
    float lightWalkWeight;
  };
  void add(int t, bool lightWalkTechnique, Vec2 pRaster, float x, double lightWalkWeight, SampleSums& sample,
           std::vector<Splat>& splats) const;
  // The end of a camera sample of pixel (px, py): its sums into the pixel's (the work item's thread).
  void addCameraSample(int px, int py, const SampleSums& sample);
  void addSplats(std::vector<Splat>& splats);  // then cleared
  // The end of a learning pass (one camera sample a pixel).
  void finishPass() { ++passes_; }
  // Every finished pass's counters, rendered at F = lightPaths(): the cost model's sums.
  void countPass(const Counters& pass);
  // Choose F for the passes after this one, from `image` (the render so far).
  void choose(const Image& image);

  // Each candidate's estimates at the last choice (empty before it), for the viewer and the stats.
  const std::vector<LightPathEstimate>& estimates() const { return estimates_; }
  // What the viewer shows: F, the passes and choices, the estimates.
  LightPathStatus status() const { return LightPathStatus{current_, passes_, choices_, estimates_}; }
  // "light paths auto: F = 0.35 (chosen 3 times from 16 learning passes)" and one line per candidate: its
  // relative variance, cost and estimated efficiency.
  std::string summary() const;

  // The cost of a camera sample at F from the counters' sums (exposed for the tests).
  double cost(float lightPaths) const;
  // E[Y_c^2] of a camera sample (the splats' X^2 included) and E[Y_c] of its camera part, from the learning
  // passes, pixel-major (exposed for the tests).
  double moment(size_t pixel, size_t candidate) const;
  double mean(size_t pixel, size_t candidate) const;

 private:
  // r_c = 1 / (w_N + (F_c / F_n) w_L) for every candidate.
  std::array<double, kLightPathCandidates.size()> ratios(double lightWalkWeight) const;
  int width_, height_;
  float current_ = 1.f;
  uint64_t passes_ = 0, choices_ = 0;
  // Over the learning passes, pixel-major, kLightPathCandidates.size() a pixel: the sums of the samples'
  // E[Y_c^2] estimates (and the splats' X^2 r), and of their E[Y_c] estimates.
  std::vector<float> second_, first_;
  // Cost sums: camera-side and light-side ray costs, camera samples, and light walks expected (F_n per
  // sample).
  double cameraCost_ = 0.0, lightCost_ = 0.0, samples_ = 0.0, lightWalks_ = 0.0;
  std::vector<LightPathEstimate> estimates_;
};

}  // namespace pathlab
