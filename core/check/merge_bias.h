// The consistency check of the merging techniques (issue 32): merging is consistent, not
// unbiased, so a merge M(s, t) is judged by its bias against the radius, not by agreement.
//
// A merge estimates the light vertex density at the merged vertex with a disk of radius r
// (Georgiev et al. 2012 eq. 11; the photon density estimate of Jensen 1996). Its expectation
// differs from the path integral by a bias that vanishes as r -> 0: O(r^2) where the integrand is
// smooth over the disk (Taylor: the disk's mean of a smooth density is the density plus
// (r^2 / 8) times its Laplacian), O(r) summed over an image region with edges and corners in it
// (there the disk or the search sphere crosses onto another surface, wrong by O(1) over a strip of
// width O(r)). So the check renders the same estimator at a ladder of fixed radii r_1 > r_2 > ...
// (alpha = 1: each pass uses r_l), measures at each the difference D_l between the merge's
// restricted estimate and each connection partner's (the pairs of technique_check.h), and fits
//     D(r) = a + b r + c r^2        (weighted least squares, weights 1 / se_l^2;
//                                    a + b r with two radii)
// to extrapolate to r -> 0. A consistent merge has a = 0 whatever its bias at the radii rendered;
// a wrong one (its normalisation doubled, say) keeps a difference that does not shrink with r,
// and its a is significant: z = a / se(a). As in checkReport, a merge's statistic in a region is
// the lower median of |z| over its connection partners there; Bonferroni over its regions, Holm
// over the merges. The differences themselves, radius by radius, are the lecture's point: the
// bias shrinks as r -> 0 while the noise grows (fewer light vertices within r).
#pragma once

#include "core/check/check_report.h"

#include <span>
#include <string>
#include <vector>

namespace pathlab {

// One rung of the ladder: the check's sums rendered with merges within `radius` (the fraction of
// the scene's bounding radius, as RenderSettings::mergeRadius).
struct MergeBiasLevel {
  double radius = 0.0;
  const TechniqueCheck* check = nullptr;
};

// A merge against one connection partner in one region at one radius (PairComparison's numbers).
struct RadiusDifference {
  double radius = 0.0;
  double difference = 0.0, standardError = 0.0;
  double partnerMean = 0.0;  // the connection's restricted estimate, for the relative difference
  bool valid = false;
  double relative() const { return partnerMean != 0.0 ? difference / partnerMean : 0.0; }
};

// The difference extrapolated to r -> 0 and its standard error (from the points' standard errors,
// the passes of different radii being independent: each radius is rendered with its own seed).
struct RadiusFit {
  double atZero = 0.0, standardError = 0.0, z = 0.0;
  int degree = 0;  // of the polynomial in r fitted: 1 with two valid radii, 2 with more
  bool valid = false;
};
RadiusFit extrapolateToZeroRadius(std::span<const RadiusDifference> points);

struct MergeVerdict {
  Technique technique;
  CheckStatus status = CheckStatus::Alone;
  // The whole image against the partner at the lower median there: the lecture's numbers.
  Technique partner;
  std::vector<RadiusDifference> wholeImage;  // one per radius, largest first
  RadiusFit wholeImageFit;
  // The verdict's statistic: the worst region's lower-median z of the extrapolated difference.
  double z = 0.0;
  int worstRegion = -1;
  Technique worstPartner;
  RadiusFit worstFit;
  double pValue = 1.0;  // two-sided, Bonferroni over its regions
  int partners = 0;     // enabled connections of its length
  // |difference| at the smallest valid radius below that at the largest (whole image).
  bool shrinking() const;
};

struct MergeBiasReport {
  std::vector<double> radii;  // largest first
  std::vector<MergeVerdict> merges;
  uint64_t passesPerRadius = 0;  // the fewest of any radius
  int blocks = 0;
  CheckOptions options;
  bool agrees() const { return disagreeing() == 0; }
  int disagreeing() const;
};

// `levels`: two or more radii, largest first, each check with the same shape (TechniqueCheck).
MergeBiasReport mergeBiasReport(std::span<const MergeBiasLevel> levels, const CheckOptions& options = {});

// One line per merge: its differences radius by radius, the extrapolation to r -> 0 and a verdict.
std::string mergeBiasText(const MergeBiasReport& report);

}  // namespace pathlab
