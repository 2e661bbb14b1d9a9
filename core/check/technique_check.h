// The consistency check of the bidirectional techniques (issue 13, part 4): does every enabled
// technique (s, t) estimate what the others estimate, on the paths both can sample?
//
// Each technique's *unweighted* estimate is unbiased for the integral over the paths of its
// length that it can sample (p_{s,t}(x) > 0; Veach 1997 sec. 10.2), whatever the weights. So for
// two techniques i and j of one length, restricted to the paths both can sample,
//     E[ sum of i's contributions to paths j can sample ] = E[ the same of j's, restricted to i ].
// A wrong technique breaks these equalities with every partner, a right one only with a wrong
// partner. The check compares pairs, not each technique with the MIS combination: the combination
// follows its dominant technique (direct lighting is mostly (1,2)), so a bug there would hide in
// the reference it is compared with.
//
// Statistics: the passes are independent (their streams are keyed by the pass), so the
// difference of the two restricted estimates over a region, one value per pass, has a mean and a
// standard error from its sum and sum of squares. Regions: a blocks x blocks grid and the whole
// image. Luminance only. check_report.h turns the sums into z-scores and a verdict.
#pragma once

#include "core/math/types.h"
#include "core/sampling/technique.h"

#include <cstdint>
#include <vector>

namespace pathlab {

// Running sums over the passes of one pair (i, j) in one region, with a = i's estimate restricted
// to the paths j can sample and b = j's restricted to i's (each the region's mean per pixel).
//
// Second moments, for a variance that does not rely on one technique having seen its rare paths:
// a's per-pass variance is sum_s Var(X_s) / N^2 over the samples s of the pass (N the region's
// pixels), and E[X^2] of i's estimator can be measured on i's own samples (ownA2) or, by
// importance reweighting, on j's: E_j[(f/p_j)^2 p_j/p_i] = integral f^2/p_i = E_i[(f/p_i)^2]
// (crossA2). Where i rarely finds a path j finds easily (a camera path hitting a tiny light that
// light tracing starts from), i's own samples miss the huge values its estimator can take, while
// j's samples weighted by p_j/p_i reveal them.
struct PairSums {
  double sumA = 0.0, sumB = 0.0;
  double sumD = 0.0, sumD2 = 0.0;        // d = a - b
  uint64_t nonzeroA = 0, nonzeroB = 0;  // passes in which a (b) was not zero
  double ownA2 = 0.0, crossA2 = 0.0;    // sums over passes of sum_s X_s^2 / N^2 for a's estimator
  double ownB2 = 0.0, crossB2 = 0.0;    // the same for b's
  double samplesA = 0.0, samplesB = 0.0;  // samples per pass behind a (b): N, or every light subpath for t = 1
  double pixels = 0.0;                    // N
};

class TechniqueCheck {
 public:
  // `enabled(x)` decides which techniques of `families` are compared; lengths 1..maxLength (at
  // most 62 connections, 31 with merges: TechniqueResult::sampleableBy has a bit per slot of a length).
  template <class Enabled>
  TechniqueCheck(int width, int height, int maxLength, int blocks, Enabled enabled,
                 TechniqueFamilies families = TechniqueFamilies::Connections)
      : TechniqueCheck(width, height, maxLength, blocks, families) {
    for (const Technique x : techniquesUpTo(maxLength, families_)) enabled_[x.index()] = enabled(x) ? 1 : 0;
  }

  // One render thread's sums over one pass (no sharing, no atomics).
  class PassSums {
   public:
    explicit PassSums(const TechniqueCheck& check) : check_(&check), a_(check.passValues(), 0.0) {}
    // A contributed technique result: its unweighted contribution's luminance, where it lands and
    // the techniques able to sample the same path (TechniqueResult::sampleableBy).
    // densityRatios[r] = p_r / p_x of the path for the technique at slot r (TechniqueResult::densityRatios).
    void add(Technique x, Vec2 pRaster, float luminance, uint64_t sampleableBy, const double* densityRatios);
    void clear() { std::fill(a_.begin(), a_.end(), 0.0); }

   private:
    friend class TechniqueCheck;
    const TechniqueCheck* check_;
    // [pair of a length][block][3]: over i's contributions c on paths j can sample, sum c,
    // sum c^2 and sum c^2 p_i / p_j (the estimate of j's second moment).
    std::vector<double> a_;
  };

  // Adds one finished pass (the sum of every thread's PassSums, which are then cleared).
  void finishPass(std::vector<PassSums*> threads);
  // Adds the passes of another check of the same shape and techniques, rendered with independent
  // streams (another seed): its pairs' sums are sums over passes, so they add.
  void absorb(const TechniqueCheck& other);

  int maxLength() const { return maxLength_; }
  TechniqueFamilies families() const { return families_; }
  int blocks() const { return blocks_; }
  int regions() const { return blocks_ * blocks_ + 1; }  // the blocks, row by row, then the whole image
  static int wholeImage(int blocks) { return blocks * blocks; }
  uint64_t passes() const { return passes_; }
  bool enabled(Technique x) const { return x.length() <= maxLength_ && enabled_[x.index()]; }
  // The sums of technique i's estimate against j's (same length, i != j) in a region.
  PairSums pair(Technique i, Technique j, int region) const;
  // The blocks grid over a width x height image: the block a position lands in, block bounds.
  int blockOf(Vec2 pRaster) const;
  void blockBounds(int block, int& x0, int& y0, int& x1, int& y1) const;

 private:
  TechniqueCheck(int width, int height, int maxLength, int blocks, TechniqueFamilies families);
  // Techniques of length k in the families checked: the pairs of a length are slots(k)^2.
  // (The equiangular technique E(1, k) is slot 2k.)
  int slots(int k) const {
    return covers(families_, TechniqueKind::Equiangular) ? 2 * k + 1 : covers(families_, TechniqueKind::Merge) ? 2 * k : k + 1;
  }
  size_t pairIndex(Technique i, Technique j) const;  // over all lengths
  size_t passValues() const { return 3 * pairCount_ * static_cast<size_t>(blocks_ * blocks_); }

  int width_, height_, maxLength_, blocks_;
  TechniqueFamilies families_;
  std::vector<uint8_t> enabled_;  // by Technique::index
  std::vector<size_t> firstPair_;  // by length: the first ordered pair (s_i, s_j) of length k
  size_t pairCount_ = 0;
  std::vector<double> blockPixels_;
  std::vector<double> pass_;   // scratch: the pass summed over threads
  std::vector<PairSums> sums_;  // [pair][region]
  uint64_t passes_ = 0;
};

}  // namespace pathlab
