// --light-paths auto: the number of light subpaths per camera sample chosen per image from the samples
// themselves (Grittmann, Yazici, Georgiev and Slusallek 2022, "Efficiency-aware multiple importance sampling
// for bidirectional rendering algorithms", sec. 4-5), among the candidates kLightPathCandidates, for the
// fixed-F sampling of light_paths.h.
//
// The second moment of a candidate from the samples of the current one. Under the balance heuristic with
// sample counts n_t, the combined estimator's second moment (one camera sample a pixel, the techniques taken
// as independent) is
//     M(n) = int f(x)^2 / sum_t n_t p_t(x) dx.
// The pass's samples (counts n: F_n for the techniques that walk a light subpath, 1 for the rest) estimate
// any integral by the balance estimator, sum over samples g(x) / sum_t n_t p_t(x), so a candidate c (F_c for
// the light-walk techniques) has the unbiased estimate
//     M(c) ~ sum over contributions X^2 * sum_t n_t p_t / sum_t c_t p_t
//          = sum over contributions X^2 / (w_N + (F_c / F_n) w_L),
// X = f / sum_t n_t p_t the weighted contribution the image received (its 1 / F_n included), w_L the sum of
// the current balance weights of the path's light-walk techniques (lightWalkWeight, mis.h) and w_N = 1 - w_L.
// F_c = F_n gives back the sum of X^2. Covariances between the techniques of one sample (path reuse) are left
// out, as in the paper: the second moment is its proxy for the variance.
//
// The choice. Per pixel p, the relative second moment m_p(c) = M_p(c) / (I_p^2 + eps), I_p the image so far
// (luminance, a 3 x 3 box mean) and eps converge's relMSE epsilon (error_metrics.h): the error that
// `converge` measures. The cost of a camera sample is a + F b in rays: a the camera walk's rays,
// kCameraSampleCost, and the shadow rays of the techniques that do not walk a light subpath (s = 0,
// next-event estimation, E(1, t)), b the light walk's rays and the shadow rays of the techniques that do, per
// light subpath; a shadow ray counts kShadowRayCost of a walk's ray (measured: docs/benchmarks.md). Rays, not
// seconds, so that the same seed gives the same choice, and the same image, at any load and thread count. The
// chosen F minimises cost(c) * sum_p m_p(c) (the paper's "work-normalised relative second moment"); the
// brightest kOutlierFraction of the pixels are left out of each candidate's sum (one firefly of the pilot
// would otherwise decide).
//
// When. The first kLightPathPilotPasses passes render at F = 1 (or the F they are given) and learn; the
// choice is made after them and again after passes 8, 16, 32, ... from every learning pass so far (every pass
// up to kLightPathsEveryPassUpTo, then one in kLightPathsStride). Each pass's F depends on earlier passes
// only, and each pass is unbiased at its own F (light_paths.h): the image stays unbiased.
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
inline constexpr uint64_t kLightPathsEveryPassUpTo = 16;
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

// One candidate's estimates at a choice.
struct LightPathEstimate {
  float lightPaths = 1.f;
  double relativeMoment = 0.0;  // mean over the pixels of m_p(c)
  double cost = 0.0;            // rays a camera sample, a + F b
  double efficiency = 0.0;      // 1 / (relativeMoment * cost), relative to F = 1's
};
struct LightPathStatus {
  float lightPaths = 1.f;  // F of the next pass
  uint64_t passes = 0, choices = 0;
  std::vector<LightPathEstimate> estimates;
};

class LightPathChoice {
 public:
  // `lightPaths`: F of the passes before the first choice.
  LightPathChoice(int width, int height, float lightPaths = 1.f);

  // F for the next pass.
  float lightPaths() const { return current_; }
  // Learning passes whose sums are in, and choices made.
  uint64_t passes() const { return passes_; }
  uint64_t choices() const { return choices_; }

  // One weighted contribution of a learning pass: its luminance X as the image received it, where it lands,
  // and the light-walk techniques' share of its balance weights (w_L). A camera contribution (t >= 2) is
  // added at once by the thread of the work item that holds its pixel; a splat (t = 1) is kept in `splats`
  // (the work item's), which the session adds in the items' order.
  struct Splat {
    uint32_t pixel;
    float x;
    float lightWalkWeight;
  };
  void add(int t, Vec2 pRaster, float x, double lightWalkWeight, std::vector<Splat>& splats);
  void addSplats(std::vector<Splat>& splats);  // then cleared
  // The end of a learning pass (one camera sample a pixel): its sums into the moments.
  void finishPass();
  void discardPass();
  // Every finished pass's counters, rendered at F = lightPaths(): the cost model's sums.
  void countPass(const Counters& pass);
  // Choose F for the passes after this one, from `image` (the render so far).
  void choose(const Image& image);

  // Each candidate's estimates at the last choice (empty before it), for the viewer and the stats.
  const std::vector<LightPathEstimate>& estimates() const { return estimates_; }
  // What the viewer shows: F, the passes and choices, the estimates.
  LightPathStatus status() const { return LightPathStatus{current_, passes_, choices_, estimates_}; }
  // "light paths auto: F = 0.35 (chosen 3 times from 16 learning passes; ...)" and one line per candidate:
  // its relative second moment, cost and estimated efficiency.
  std::string summary() const;

  // The cost of a camera sample at F from the counters' sums (exposed for the tests).
  double cost(float lightPaths) const;
  // M_p(c) per learning pass, pixel-major (exposed for the tests).
  double moment(size_t pixel, size_t candidate) const;

 private:
  void addAt(size_t pixel, float x, double lightWalkWeight);
  int width_, height_;
  float current_ = 1.f;
  uint64_t passes_ = 0, choices_ = 0;
  // sum X^2 / (w_N + F_c / F_n w_L), pixel-major, kLightPathCandidates.size() a pixel: this pass's (dropped
  // if it is cancelled) and over the learning passes.
  std::vector<double> passMoments_, moments_;
  // Cost sums: camera-side and light-side ray costs, camera samples, and light walks expected (F_n per
  // sample).
  double cameraCost_ = 0.0, lightCost_ = 0.0, samples_ = 0.0, lightWalks_ = 0.0;
  std::vector<LightPathEstimate> estimates_;
};

}  // namespace pathlab
