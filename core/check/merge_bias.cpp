// mergeBiasReport: each merge's differences from its connection partners at a ladder of radii,
// extrapolated to r -> 0 (the model and why in merge_bias.h).
#include "core/check/merge_bias.h"

#include "core/sampling/technique_label.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

// Two-sided normal tail probability of |z|.
double twoSidedTail(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

// Inverts the symmetric positive definite m x m matrix `a` (m <= 3) by Gauss-Jordan elimination;
// false when it is singular.
bool invert(std::array<std::array<double, 3>, 3>& a, int m) {
  std::array<std::array<double, 3>, 3> inv{};
  for (int i = 0; i < m; ++i) inv[i][i] = 1.0;
  for (int c = 0; c < m; ++c) {
    int pivot = c;
    for (int r = c + 1; r < m; ++r)
      if (std::abs(a[r][c]) > std::abs(a[pivot][c])) pivot = r;
    if (!(std::abs(a[pivot][c]) > 1e-300)) return false;
    std::swap(a[c], a[pivot]);
    std::swap(inv[c], inv[pivot]);
    const double d = a[c][c];
    for (int k = 0; k < m; ++k) a[c][k] /= d, inv[c][k] /= d;
    for (int r = 0; r < m; ++r) {
      if (r == c) continue;
      const double f = a[r][c];
      for (int k = 0; k < m; ++k) a[r][k] -= f * a[c][k], inv[r][k] -= f * inv[c][k];
    }
  }
  a = inv;
  return true;
}

struct PartnerFit {
  Technique partner;
  RadiusFit fit;
  std::vector<RadiusDifference> points;
};

// The lower median by |z| of the valid fits, as checkReport's lowerMedian.
const PartnerFit* lowerMedianFit(std::vector<PartnerFit>& fits) {
  auto end = std::partition(fits.begin(), fits.end(), [](const PartnerFit& f) { return f.fit.valid; });
  const size_t m = static_cast<size_t>(end - fits.begin());
  if (m == 0) return nullptr;
  std::sort(fits.begin(), end, [](const PartnerFit& a, const PartnerFit& b) { return std::abs(a.fit.z) < std::abs(b.fit.z); });
  return &fits[(m + 1) / 2 - 1];
}

std::string regionLabel(int region, int blocks) {
  if (region < 0) return "-";
  if (region == TechniqueCheck::wholeImage(blocks)) return "whole image";
  return fmt::format("block ({},{})", region % blocks, region / blocks);
}

}  // namespace

RadiusFit extrapolateToZeroRadius(std::span<const RadiusDifference> points) {
  RadiusFit fit;
  double scale = 0.0;  // r in units of the largest radius, for a well-conditioned normal matrix
  int n = 0;
  for (const RadiusDifference& p : points)
    if (p.valid && p.standardError > 0.0) ++n, scale = std::max(scale, p.radius);
  if (n < 2 || !(scale > 0.0)) return fit;
  fit.degree = std::min(2, n - 1);
  const int m = fit.degree + 1;
  // Weighted least squares: minimise sum_l (D_l - sum_k beta_k r_l^k)^2 / se_l^2. The normal
  // matrix M = X^T W X; beta = M^-1 X^T W D, and Cov(beta) = M^-1 for independent points.
  std::array<std::array<double, 3>, 3> normal{};
  std::array<double, 3> rhs{};
  for (const RadiusDifference& p : points) {
    if (!(p.valid && p.standardError > 0.0)) continue;
    const double w = 1.0 / (p.standardError * p.standardError), r = p.radius / scale;
    const std::array<double, 3> x{1.0, r, r * r};
    for (int i = 0; i < m; ++i) {
      rhs[i] += w * x[i] * p.difference;
      for (int j = 0; j < m; ++j) normal[i][j] += w * x[i] * x[j];
    }
  }
  if (!invert(normal, m)) return fit;
  for (int j = 0; j < m; ++j) fit.atZero += normal[0][j] * rhs[j];
  fit.standardError = std::sqrt(std::max(0.0, normal[0][0]));
  if (!(fit.standardError > 0.0)) return fit;
  fit.z = fit.atZero / fit.standardError;
  fit.valid = std::isfinite(fit.z);
  return fit;
}

bool MergeVerdict::shrinking() const {
  const RadiusDifference* first = nullptr;
  const RadiusDifference* last = nullptr;
  for (const RadiusDifference& p : wholeImage) {
    if (!p.valid) continue;
    if (!first) first = &p;
    last = &p;
  }
  return first && last && first != last && std::abs(last->difference) < std::abs(first->difference);
}

int MergeBiasReport::disagreeing() const {
  return static_cast<int>(
      std::count_if(merges.begin(), merges.end(), [](const MergeVerdict& v) { return v.status == CheckStatus::Disagrees; }));
}

MergeBiasReport mergeBiasReport(std::span<const MergeBiasLevel> levels, const CheckOptions& options) {
  if (levels.size() < 2) throw std::invalid_argument("the merges' bias needs at least two radii");
  const TechniqueCheck& first = *levels.front().check;
  MergeBiasReport report;
  report.options = options;
  report.blocks = first.blocks();
  report.passesPerRadius = first.passes();
  for (const MergeBiasLevel& l : levels) {
    if (l.check->blocks() != first.blocks() || l.check->maxLength() != first.maxLength())
      throw std::invalid_argument("the merges' bias: the checks of the radii differ in shape");
    report.radii.push_back(l.radius);
    report.passesPerRadius = std::min(report.passesPerRadius, l.check->passes());
  }
  const int regions = first.regions(), whole = TechniqueCheck::wholeImage(first.blocks());
  for (const Technique x : techniquesUpTo(first.maxLength(), first.families())) {
    if (!x.isMerge() || !first.enabled(x)) continue;
    MergeVerdict v;
    v.technique = x;
    int sharing = 0;
    bool sharesPaths = false, comparable = false;
    for (const Technique j : techniquesOfLength(x.length(), TechniqueFamilies::Connections)) {
      if (!first.enabled(j)) continue;
      ++v.partners;
      bool shares = false;
      for (const MergeBiasLevel& l : levels) {
        const PairSums p = l.check->pair(x, j, whole);
        shares |= p.nonzeroA > 0 || p.nonzeroB > 0;
      }
      sharing += shares ? 1 : 0;
    }
    double worst = -1.0;
    for (int region = 0; region < regions; ++region) {
      std::vector<PartnerFit> fits;
      for (const Technique j : techniquesOfLength(x.length(), TechniqueFamilies::Connections)) {
        if (!first.enabled(j)) continue;
        PartnerFit f{j, {}, {}};
        for (const MergeBiasLevel& l : levels) {
          const PairSums p = l.check->pair(x, j, region);
          sharesPaths |= p.nonzeroA > 0 || p.nonzeroB > 0;
          const PairComparison c = comparePair(*l.check, x, j, region, options);
          f.points.push_back(RadiusDifference{l.radius, c.difference, c.standardError, c.partnerMean, c.valid});
        }
        f.fit = extrapolateToZeroRadius(f.points);
        fits.push_back(std::move(f));
      }
      // As in checkReport: with two or more partners sharing paths, a region is judged only where
      // two comparisons are possible.
      const int valid = static_cast<int>(std::count_if(fits.begin(), fits.end(), [](const PartnerFit& f) { return f.fit.valid; }));
      if (valid < std::min(2, sharing)) continue;
      const PartnerFit* median = lowerMedianFit(fits);
      if (!median) continue;
      comparable = true;
      if (region == whole) {
        v.partner = median->partner;
        v.wholeImage = median->points;
        v.wholeImageFit = median->fit;
      }
      const double statistic = std::abs(median->fit.z);
      if (statistic > worst) {
        worst = statistic;
        v.z = median->fit.z;
        v.worstRegion = region;
        v.worstPartner = median->partner;
        v.worstFit = median->fit;
      }
    }
    if (comparable) {
      v.pValue = std::min(1.0, twoSidedTail(v.z) * static_cast<double>(regions));
      v.status = CheckStatus::Agrees;
    } else {
      v.status = (v.partners > 0 && sharesPaths) ? CheckStatus::Inconclusive : CheckStatus::Alone;
    }
    report.merges.push_back(std::move(v));
  }
  // Holm's step-down over the merges compared, at the check's level (the connections have theirs).
  std::vector<size_t> order;
  for (size_t i = 0; i < report.merges.size(); ++i)
    if (report.merges[i].status == CheckStatus::Agrees) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return report.merges[a].pValue < report.merges[b].pValue; });
  for (size_t r = 0; r < order.size(); ++r) {
    MergeVerdict& v = report.merges[order[r]];
    if (!(v.pValue <= options.alpha / static_cast<double>(order.size() - r))) break;
    v.status = CheckStatus::Disagrees;
  }
  return report;
}

std::string mergeBiasText(const MergeBiasReport& report) {
  auto percent = [](double value, double se, double reference) {
    if (reference == 0.0) return fmt::format("{:>+9.2e} ± {:.1e}", value, se);
    return fmt::format("{:>+7.2f}% ± {:.2f}%", 100.0 * value / reference, 100.0 * se / std::abs(reference));
  };
  std::string out = fmt::format(
      "merges: bias against the radius (relative difference from a connection of the same length on the paths both "
      "sample, ± one standard error; radii fixed per run, alpha = 1, as fractions of the scene's bounding radius)\n");
  out += fmt::format("{:<8} {:>3}  {:<6}", "merge", "k", "vs");
  for (const double r : report.radii) out += fmt::format(" {:<19}", fmt::format("r = {:g}", r));
  out += fmt::format(" {:<19} {:>7}  {:<16} {}\n", "r -> 0", "z", "worst region", "verdict");
  for (const MergeVerdict& v : report.merges) {
    const bool compared = v.status == CheckStatus::Agrees || v.status == CheckStatus::Disagrees;
    out += fmt::format("{:<8} {:>3}  {:<6}", techniqueLabel(v.technique), v.technique.length(),
                       compared && !v.wholeImage.empty() ? techniqueLabel(v.partner) : "-");
    // The relative differences are against the partner's estimate at the largest radius whose
    // comparison is valid: the same yardstick for every column.
    double reference = 0.0;
    for (const RadiusDifference& p : v.wholeImage)
      if (p.valid && reference == 0.0) reference = p.partnerMean;
    for (size_t l = 0; l < report.radii.size(); ++l) {
      const RadiusDifference* p = l < v.wholeImage.size() ? &v.wholeImage[l] : nullptr;
      out += fmt::format(" {:<19}", p && p->valid ? percent(p->difference, p->standardError, reference) : "-");
    }
    if (!compared) {
      out += fmt::format(" {:<19} {:>7}  {:<16} {}\n", "-", "-", "-", checkStatusName(v.status));
      continue;
    }
    const std::string atZero =
        v.wholeImageFit.valid ? percent(v.wholeImageFit.atZero, v.wholeImageFit.standardError, reference) : "-";
    std::string verdict = checkStatusName(v.status);
    if (v.status == CheckStatus::Disagrees) verdict += ": its difference does not vanish as r -> 0";
    else if (v.shrinking()) verdict += ", bias shrinking with r";
    out += fmt::format(" {:<19} {:>+7.2f}  {:<16} {}\n", atZero, v.z, regionLabel(v.worstRegion, report.blocks), verdict);
  }
  const int bad = report.disagreeing();
  out += fmt::format("{} passes per radius, fit D(r) = a + b r + c r^2 extrapolated to r -> 0 (a + b r with two radii), "
                     "level {} (Holm over the merges, Bonferroni over regions)\n",
                     report.passesPerRadius, report.options.alpha);
  if (bad == 0) out += "verdict: every compared merge is consistent with the connections (its bias vanishes as r -> 0)\n";
  else
    out += fmt::format("verdict: {} merge{} keep{} a difference from the connections as r -> 0\n", bad, bad == 1 ? "" : "s",
                       bad == 1 ? "s" : "");
  return out;
}

}  // namespace pathlab
