// The verdict of the consistency check (technique_check.h): per technique, the z-scores of its
// pairwise comparisons, the region where it disagrees most, and whether that survives the
// correction for the number of comparisons (Holm 1979 over the techniques, Bonferroni over the
// regions within each).
#pragma once

#include "core/check/technique_check.h"

#include <string>
#include <vector>

namespace pathlab {

struct CheckOptions {
  double alpha = 0.01;  // family-wise false-alarm rate of the whole check
  // A pair is compared in a region only when both restricted estimates were non-zero in at least
  // this many passes: a technique that has barely found its paths there (a small light hit by
  // chance) has a sample variance that says nothing yet, and its z-score would be meaningless.
  uint64_t minNonzeroPasses = 20;
  uint64_t minPasses = 16;
};

enum class CheckStatus {
  Agrees,        // no comparison significant at the corrected level
  Disagrees,     // significant: this technique (or, at length 1, one of the two) is wrong
  Inconclusive,  // it has partners, but no region with enough non-zero passes yet
  Alone,         // no other enabled technique of its length shares any of its paths
};
const char* checkStatusName(CheckStatus s);

// One pair (i against a partner j) in one region: i's estimate on the paths both can sample minus
// j's, per pixel and pass (luminance), its standard error over the passes and z = diff / se.
struct PairComparison {
  Technique partner;
  double difference = 0.0, standardError = 0.0, z = 0.0;
  double partnerMean = 0.0;  // j's restricted estimate, for the relative difference
  bool valid = false;
};

struct TechniqueVerdict {
  Technique technique;
  CheckStatus status = CheckStatus::Alone;
  // The technique's statistic in a region is the lower median of |z| over its valid partners
  // there: a wrong technique disagrees with every partner, a right one only with wrong ones, so
  // one wrong technique does not drag its partners with it (at length 1, with a single partner,
  // both are flagged: two techniques cannot tell which of them is wrong). A technique with two
  // or more partners is judged only in regions where at least two comparisons are possible.
  double z = 0.0;                 // the statistic in its worst region (signed as that pair's z)
  int worstRegion = -1;           // TechniqueCheck region (blocks row by row, then the whole image)
  PairComparison worst;           // the pair at the lower median there
  double wholeImageZ = 0.0;       // the statistic over the whole image (0 when not comparable)
  std::vector<double> blockZ;     // |statistic| per block; negative where not comparable
  double pValue = 1.0;            // two-sided, Bonferroni over its regions
  int partners = 0;               // enabled partners of its length
};

struct CheckReport {
  std::vector<TechniqueVerdict> techniques;  // every enabled connection, in index order (merges: merge_bias.h)
  CheckOptions options;
  uint64_t passes = 0;
  int blocks = 0;
  bool agrees() const;
  int disagreeing() const;
};

CheckReport checkReport(const TechniqueCheck& check, const CheckOptions& options = {});

// The comparison of i with j in one region (for the report, the viewer's hover text and tests).
PairComparison comparePair(const TechniqueCheck& check, Technique i, Technique j, int region, const CheckOptions& options);

// One line per technique and a verdict, as `pathlab check` prints them.
std::string checkReportText(const CheckReport& report);

}  // namespace pathlab
