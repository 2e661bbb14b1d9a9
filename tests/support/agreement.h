// Several estimators of one image rendered side by side and compared pairwise by region z-tests,
// with one Bonferroni threshold for the whole family of comparisons (region_estimate.h).
#pragma once

#include "tests/support/region_estimate.h"

#include <functional>
#include <string>
#include <vector>

namespace pathlab::test {

// The family-wise false-failure rate the agreement tests use (runAgreement's familyAlpha).
inline constexpr double kFamilyAlpha = 1e-3;

struct EstimatorSpec {
  std::string name;
  RenderSettings settings;  // seeds must differ between estimators (independent errors)
  int passes = 32;
};

struct PairSpec {
  std::string a, b;  // estimator names
  int labelSet = 0;  // index into the label sets given to runAgreement
  // Power: the median over regions and channels (those with a mean not negligible) of the
  // standard error of a - b relative to the mean must be below this, so that a typical region
  // would show a bias of a few times this fraction (the whole image: several times less).
  double maxRelativeSe = 0.05;
};

struct PairResult {
  PairSpec spec;
  Agreement agreement;
  double relativeSe = 0.0;        // largest over the channels, whole image
  double medianRelativeSe = 0.0;  // median over regions and channels
  double meanA[3] = {0, 0, 0}, meanB[3] = {0, 0, 0};
};

struct AgreementRun {
  std::vector<RegionMeans> estimates;  // [estimator * labelSets + labelSet]
  std::vector<double> seconds;         // per estimator
  std::vector<PairResult> pairs;
  int comparisons = 0;
  double threshold = 0.0;  // bonferroniZ(familyAlpha, comparisons)
  std::string summary() const;
};

// familyAlpha: the probability that unbiased estimators fail at least one comparison of the run
// (Bonferroni: every comparison is tested at familyAlpha / comparisons, two-sided).
AgreementRun runAgreement(const Scene& scene, const std::vector<EstimatorSpec>& estimators,
                          const std::vector<PixelLabels>& labelSets, const std::vector<PairSpec>& pairs,
                          double familyAlpha);

// Prints the run's seconds per estimator and its summary to stdout, headed by `what`.
void report(const AgreementRun& run, const std::string& what);

// `base` rendered by another integrator and heuristic with its own seed, for `passes` passes.
EstimatorSpec estimatorSpec(const std::string& name, const RenderSettings& base, IntegratorKind kind, MisHeuristic h,
                            uint64_t seed, int passes);

// Base of the fixed seeds of a test: 0, or PATHLAB_TEST_SEED when set (to rerun a test with other
// seeds and see that its threshold does not depend on one lucky seed).
uint64_t testSeedBase();

// gtest expectations on a run: every pair within the threshold, enough power, nothing discarded.
void expectAgreement(const AgreementRun& run, const std::string& what);

// A bundled scene, assets/NAME.gltf (environment.gltf lit by assets/sky.hdr, as it is shown).
Scene bundledScene(const std::string& name);

// One bundled scene's case for a bidirectional estimator's agreement: its image, maximum length,
// passes, the path tracer's passes (0: the path tracer misses some of its paths in a short render:
// caustics, fog's spot, the door's gap, a point lamp) and regions a side.
struct BundledCase {
  const char* name;
  int width, height, maxLength, passes, ptPasses;
  int cells = 3;
};
// The estimator `name` (bpt under the balance heuristic, then `configure`) against bpt under the
// balance heuristic (another seed) and, with ptPasses, the path tracer, region by region, pixels
// that see an emitter or a delta surface directly left out; gtest expectations. `seedSalt` keeps
// each test's seeds its own.
void expectBundledAgreement(const BundledCase& c, const std::string& name,
                            const std::function<void(RenderSettings&)>& configure, uint64_t seedSalt);
// Every bundled scene in three groups, with the passes a heuristic fixed pass by pass from the passes
// before (variance-aware and optimal MIS) needs to agree: expectBundledAgreement over each group.
enum class BundledGroup { Diffuse, GlossyAndSpecular, MediaAndHardVisibility };
void expectBundledGroupAgreement(BundledGroup group, const std::string& name,
                                 const std::function<void(RenderSettings&)>& configure, uint64_t seedSalt);

}  // namespace pathlab::test
