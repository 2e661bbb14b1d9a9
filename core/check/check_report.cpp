// checkReport: pairwise z-scores, the lower median per technique and region, Holm over techniques.
#include "core/check/check_report.h"

#include "core/sampling/technique_label.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace pathlab {

const char* checkStatusName(CheckStatus s) {
  switch (s) {
    case CheckStatus::Agrees: return "agrees";
    case CheckStatus::Disagrees: return "DISAGREES";
    case CheckStatus::Inconclusive: return "too few samples";
    case CheckStatus::Alone: return "nothing to compare with";
  }
  return "?";
}

bool CheckReport::agrees() const { return disagreeing() == 0; }

int CheckReport::disagreeing() const {
  return static_cast<int>(std::count_if(techniques.begin(), techniques.end(),
                                        [](const TechniqueVerdict& v) { return v.status == CheckStatus::Disagrees; }));
}

PairComparison comparePair(const TechniqueCheck& check, Technique i, Technique j, int region, const CheckOptions& options) {
  PairComparison c;
  c.partner = j;
  const uint64_t n = check.passes();
  const PairSums p = check.pair(i, j, region);
  if (n < std::max<uint64_t>(options.minPasses, 2) || p.nonzeroA < options.minNonzeroPasses ||
      p.nonzeroB < options.minNonzeroPasses)
    return c;
  const double nd = static_cast<double>(n);
  const double mean = p.sumD / nd;
  const double sampleVariance = std::max(0.0, (p.sumD2 - nd * mean * mean) / (nd - 1.0));
  // The per-pass variance of a restricted estimate from its estimator's second moment, the larger
  // of its own samples' and the partner's reweighted ones (PairSums): Var = E[sum X^2] / N^2 -
  // E[a]^2 / samples. The standard error uses the larger of that model (a and b taken as
  // uncorrelated) and the plain sample variance of d: a technique that has not yet met its rare,
  // large values does not look certain.
  auto modelVariance = [&](double own2, double cross2, double sum, double samples) {
    const double m = sum / nd;
    return std::max(0.0, std::max(own2, cross2) / nd - m * m / std::max(samples, 1.0));
  };
  const double model = modelVariance(p.ownA2, p.crossA2, p.sumA, p.samplesA) + modelVariance(p.ownB2, p.crossB2, p.sumB, p.samplesB);
  c.difference = mean;
  c.standardError = std::sqrt(std::max(sampleVariance, model) / nd);
  c.partnerMean = p.sumB / nd;
  if (!(c.standardError > 0.0)) return c;
  c.z = mean / c.standardError;
  c.valid = std::isfinite(c.z);
  return c;
}

namespace {

// The lower median by |z| of the valid comparisons: the ceil(m/2)-th smallest (the smallest of
// two, the middle of three).
const PairComparison* lowerMedian(std::vector<PairComparison>& pairs) {
  auto end = std::partition(pairs.begin(), pairs.end(), [](const PairComparison& c) { return c.valid; });
  const size_t m = static_cast<size_t>(end - pairs.begin());
  if (m == 0) return nullptr;
  std::sort(pairs.begin(), end, [](const PairComparison& a, const PairComparison& b) { return std::abs(a.z) < std::abs(b.z); });
  return &pairs[(m + 1) / 2 - 1];
}

// Two-sided normal tail probability of |z|.
double twoSided(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

}  // namespace

CheckReport checkReport(const TechniqueCheck& check, const CheckOptions& options) {
  CheckReport report;
  report.options = options;
  report.passes = check.passes();
  report.blocks = check.blocks();
  const int regions = check.regions(), whole = TechniqueCheck::wholeImage(check.blocks());
  // The connections and the equiangular techniques E(1, k) only (unbiased techniques): a merge is
  // consistent, not unbiased, and is judged by its bias against the radius over several renders
  // (merge_bias.h), never at one radius.
  constexpr TechniqueFamilies kUnbiased = TechniqueFamilies::Connections | TechniqueFamilies::Equiangular;
  for (const Technique x : techniquesUpTo(check.maxLength(), kUnbiased)) {
    if (!check.enabled(x)) continue;
    TechniqueVerdict v;
    v.technique = x;
    v.blockZ.assign(static_cast<size_t>(check.blocks() * check.blocks()), -1.0);
    const int k = x.length();
    // Partners that share any path with it (the whole image's sums say so): a point light leaves
    // s = 0 nothing to share, and such a partner does not count toward the two comparisons a
    // region needs.
    int sharing = 0;
    // Partners are the other unbiased techniques of its length: merges never judge a connection.
    for (const Technique j : techniquesOfLength(k, kUnbiased)) {
      if (j == x || !check.enabled(j)) continue;
      ++v.partners;
      const PairSums whole = check.pair(x, j, TechniqueCheck::wholeImage(check.blocks()));
      sharing += (whole.nonzeroA > 0 || whole.nonzeroB > 0) ? 1 : 0;
    }
    bool sharesPaths = false, comparable = false;
    double worst = -1.0;
    for (int region = 0; region < regions; ++region) {
      std::vector<PairComparison> pairs;
      for (const Technique j : techniquesOfLength(k, kUnbiased)) {
        if (j == x || !check.enabled(j)) continue;
        const PairSums p = check.pair(x, j, region);
        sharesPaths |= p.nonzeroA > 0 || p.nonzeroB > 0;
        pairs.push_back(comparePair(check, x, j, region, options));
      }
      // One valid partner cannot tell which of the two is wrong: with more partners sharing paths
      // with it, a region where only one comparison is possible is not judged (else a right
      // technique would be flagged wherever it can only be compared with a wrong one).
      const int valid = static_cast<int>(std::count_if(pairs.begin(), pairs.end(), [](const PairComparison& c) { return c.valid; }));
      if (valid < std::min(2, sharing)) continue;
      const PairComparison* median = lowerMedian(pairs);
      if (!median) continue;
      comparable = true;
      const double statistic = std::abs(median->z);
      if (region == whole) v.wholeImageZ = median->z;
      else v.blockZ[static_cast<size_t>(region)] = statistic;
      if (statistic > worst) {
        worst = statistic;
        v.z = median->z;
        v.worstRegion = region;
        v.worst = *median;
      }
    }
    if (comparable) {
      v.pValue = std::min(1.0, twoSided(v.z) * static_cast<double>(regions));
      v.status = CheckStatus::Agrees;  // until Holm says otherwise
    } else {
      v.status = (v.partners > 0 && sharesPaths) ? CheckStatus::Inconclusive : CheckStatus::Alone;
    }
    report.techniques.push_back(std::move(v));
  }
  // Holm's step-down over the techniques that were compared: the r-th smallest p (from 0) is
  // significant when it and every smaller one are below alpha / (m - r).
  std::vector<size_t> order;
  for (size_t i = 0; i < report.techniques.size(); ++i)
    if (report.techniques[i].status == CheckStatus::Agrees) order.push_back(i);
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return report.techniques[a].pValue < report.techniques[b].pValue; });
  const size_t m = order.size();
  for (size_t r = 0; r < m; ++r) {
    TechniqueVerdict& v = report.techniques[order[r]];
    if (!(v.pValue <= options.alpha / static_cast<double>(m - r))) break;
    v.status = CheckStatus::Disagrees;
  }
  return report;
}

namespace {

std::string regionName(int region, int blocks) {
  if (region < 0) return "-";
  if (region == TechniqueCheck::wholeImage(blocks)) return "whole image";
  return fmt::format("block ({},{})", region % blocks, region / blocks);
}

std::string techniqueName(Technique x) { return techniqueLabel(x); }

}  // namespace

std::string checkReportText(const CheckReport& report) {
  std::string out = fmt::format(
      "{:<8} {:>3}  {:<9} {:>12} {:>11} {:>8} {:>8}  {:<16} {}\n", "(s,t)", "k", "vs", "difference", "std. error",
      "rel.", "z", "worst region", "verdict");
  for (const TechniqueVerdict& v : report.techniques) {
    const bool compared = v.status == CheckStatus::Agrees || v.status == CheckStatus::Disagrees;
    if (!compared) {
      out += fmt::format("{:<8} {:>3}  {:<9} {:>12} {:>11} {:>8} {:>8}  {:<16} {}\n", techniqueName(v.technique),
                         v.technique.length(), "-", "-", "-", "-", "-", "-", checkStatusName(v.status));
      continue;
    }
    const double relative = v.worst.partnerMean != 0.0 ? v.worst.difference / v.worst.partnerMean : 0.0;
    out += fmt::format("{:<8} {:>3}  {:<9} {:>+12.4e} {:>11.3e} {:>+7.1f}% {:>+8.2f}  {:<16} {}\n",
                       techniqueName(v.technique), v.technique.length(), techniqueName(v.worst.partner),
                       v.worst.difference, v.worst.standardError, 100.0 * relative, v.z,
                       regionName(v.worstRegion, report.blocks), checkStatusName(v.status));
  }
  const int bad = report.disagreeing();
  const size_t compared = static_cast<size_t>(std::count_if(report.techniques.begin(), report.techniques.end(), [](const TechniqueVerdict& v) {
    return v.status == CheckStatus::Agrees || v.status == CheckStatus::Disagrees;
  }));
  out += fmt::format("{} passes, {} x {} blocks and the whole image, family-wise level {} (Holm over {} techniques, "
                     "Bonferroni over regions)\n",
                     report.passes, report.blocks, report.blocks, report.options.alpha, compared);
  if (bad == 0)
    out += fmt::format("verdict: every compared technique agrees with its partners\n");
  else
    out += fmt::format("verdict: {} technique{} disagree{} with {} partners\n", bad, bad == 1 ? "" : "s",
                       bad == 1 ? "s" : "", bad == 1 ? "its" : "their");
  return out;
}

}  // namespace pathlab
