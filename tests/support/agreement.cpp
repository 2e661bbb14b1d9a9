// Renders every estimator once, then runs the pairwise region z-tests.
#include "tests/support/agreement.h"

#include "core/lights/environment_file.h"
#include "core/scene/gltf_loader.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <stdexcept>

namespace pathlab::test {

AgreementRun runAgreement(const Scene& scene, const std::vector<EstimatorSpec>& estimators,
                          const std::vector<PixelLabels>& labelSets, const std::vector<PairSpec>& pairs,
                          double familyAlpha) {
  AgreementRun run;
  for (const EstimatorSpec& e : estimators) {
    std::vector<RegionMeans> m = renderRegionMeans(scene, e.settings, e.passes, labelSets);
    run.seconds.push_back(m.front().seconds);
    for (RegionMeans& r : m) run.estimates.push_back(std::move(r));
  }
  auto find = [&](const std::string& name) {
    for (size_t i = 0; i < estimators.size(); ++i)
      if (estimators[i].name == name) return i;
    throw std::invalid_argument("no estimator named " + name);
  };
  for (const PairSpec& p : pairs) {
    const RegionMeans& a = run.estimates[find(p.a) * labelSets.size() + static_cast<size_t>(p.labelSet)];
    const RegionMeans& b = run.estimates[find(p.b) * labelSets.size() + static_cast<size_t>(p.labelSet)];
    PairResult r;
    r.spec = p;
    r.agreement = compareRegions(a, b);
    double largest = 0.0;
    for (size_t c = 0; c < 3; ++c) largest = std::max({largest, std::abs(a.whole[c].mean), std::abs(b.whole[c].mean)});
    for (size_t c = 0; c < 3; ++c) {
      r.meanA[c] = a.whole[c].mean;
      r.meanB[c] = b.whole[c].mean;
      const double mean = std::max(std::abs(a.whole[c].mean), std::abs(b.whole[c].mean));
      if (mean < 1e-3 * largest || mean == 0.0) continue;  // a channel with (almost) nothing in it
      const double se = std::hypot(a.whole[c].standardError, b.whole[c].standardError);
      r.relativeSe = std::max(r.relativeSe, se / mean);
    }
    std::vector<double> relative;
    for (size_t k = 0; k < a.region.size() && k < b.region.size(); ++k)
      for (size_t c = 0; c < 3; ++c) {
        const double mean = std::max(std::abs(a.region[k][c].mean), std::abs(b.region[k][c].mean));
        if (a.region[k][c].count == 0 || mean < 1e-3 * largest || mean == 0.0) continue;
        relative.push_back(std::hypot(a.region[k][c].standardError, b.region[k][c].standardError) / mean);
      }
    if (!relative.empty()) {
      std::nth_element(relative.begin(), relative.begin() + static_cast<std::ptrdiff_t>(relative.size() / 2),
                       relative.end());
      r.medianRelativeSe = relative[relative.size() / 2];
    } else {
      r.medianRelativeSe = std::numeric_limits<double>::infinity();
    }
    run.comparisons += r.agreement.comparisons;
    run.pairs.push_back(r);
  }
  run.threshold = bonferroniZ(familyAlpha, run.comparisons);
  return run;
}

EstimatorSpec estimatorSpec(const std::string& name, const RenderSettings& base, IntegratorKind kind, MisHeuristic h,
                            uint64_t seed, int passes) {
  RenderSettings s = base;
  s.integrator = kind;
  s.mis.heuristic = h;
  s.seed = seed;
  return {name, s, passes};
}

uint64_t testSeedBase() {
  const char* env = std::getenv("PATHLAB_TEST_SEED");
  return env ? std::strtoull(env, nullptr, 10) : 0;
}

std::string AgreementRun::summary() const {
  std::string s = fmt::format("{} comparisons, threshold |z| < {:.2f}\n", comparisons, threshold);
  for (const PairResult& p : pairs)
    s += fmt::format(
        "  {} vs {} (labels {}): max |z| {:.2f}, relative se {:.4f} (whole image), {:.4f} (median region); worst {}\n",
        p.spec.a, p.spec.b, p.spec.labelSet, p.agreement.maxAbsZ, p.relativeSe, p.medianRelativeSe, p.agreement.worst);
  return s;
}

void expectAgreement(const AgreementRun& run, const std::string& what) {
  std::string failures;
  for (const PairResult& p : run.pairs) {
    if (!(p.agreement.maxAbsZ < run.threshold))
      failures += fmt::format("  {} vs {} disagree: {}\n", p.spec.a, p.spec.b, p.agreement.worst);
    if (!(p.medianRelativeSe < p.spec.maxRelativeSe))
      failures += fmt::format("  {} vs {} too noisy to detect a bias: median region relative se {:.4f} >= {:.4f}\n",
                              p.spec.a, p.spec.b, p.medianRelativeSe, p.spec.maxRelativeSe);
    if (p.agreement.comparisons == 0) failures += fmt::format("  {} vs {}: nothing compared\n", p.spec.a, p.spec.b);
  }
  for (const RegionMeans& m : run.estimates)
    if (m.discarded != 0) failures += fmt::format("  {} samples discarded (NaN, Inf or negative)\n", m.discarded);
  if (!failures.empty()) ADD_FAILURE() << what << ":\n" << failures << run.summary();
}

void report(const AgreementRun& run, const std::string& what) {
  std::string times;
  for (double t : run.seconds) times += " " + std::to_string(t).substr(0, 5);
  std::cout << what << ": seconds" << times << "\n" << run.summary();
}

Scene bundledScene(const std::string& name) {
  const std::string source = PATHLAB_SOURCE_DIR;
  LoadOptions load;
  if (name == "environment")
    load.environment = std::make_shared<EnvironmentDesc>(readEnvironment(source + "/assets/sky.hdr"));
  return Scene(loadGltf(source + "/assets/" + name + ".gltf", load));
}

void expectBundledAgreement(const BundledCase& c, const std::string& name,
                            const std::function<void(RenderSettings&)>& configure, uint64_t seedSalt) {
  const Scene scene = bundledScene(c.name);
  RenderSettings base;
  base.width = c.width;
  base.height = c.height;
  base.maxLength = c.maxLength;
  PixelLabels grid = gridLabels(base.width, base.height, c.cells, c.cells);
  grid = withoutSeenDirectly(scene, base, grid, emitterOrDelta, 16);
  const uint64_t seed = 1000 * testSeedBase() + seedSalt;
  EstimatorSpec tested = estimatorSpec(name, base, IntegratorKind::Bpt, MisHeuristic::Balance, seed, c.passes);
  configure(tested.settings);
  std::vector<EstimatorSpec> estimators = {
      tested, estimatorSpec("balance", base, IntegratorKind::Bpt, MisHeuristic::Balance, seed + 1, c.passes)};
  std::vector<PairSpec> pairs = {{name, "balance"}};
  if (c.ptPasses > 0) {
    estimators.push_back(estimatorSpec("pt", base, IntegratorKind::Pt, MisHeuristic::Balance, seed + 2, c.ptPasses));
    pairs.push_back({name, "pt"});
  }
  const AgreementRun run = runAgreement(scene, estimators, {grid}, pairs, kFamilyAlpha);
  report(run, std::string(c.name) + ", " + name);
  expectAgreement(run, std::string(c.name) + ", " + name);
}

void expectBundledGroupAgreement(BundledGroup group, const std::string& name,
                                 const std::function<void(RenderSettings&)>& configure, uint64_t seedSalt) {
  std::vector<BundledCase> cases;
  switch (group) {
    case BundledGroup::Diffuse:
      cases = {{"cornell-box", 16, 16, 8, 256, 768},
               {"bidir-lamp", 15, 15, 8, 192, 768},
               {"environment", 16, 12, 6, 256, 2048},
               {"isometric", 16, 16, 6, 256, 512}};
      break;
    case BundledGroup::GlossyAndSpecular:
      cases = {{"cornell-spheres", 16, 16, 8, 512, 3072},
               {"veach-mis", 24, 16, 8, 512, 0},
               {"caustic", 16, 16, 8, 768, 0, 2}};
      break;
    case BundledGroup::MediaAndHardVisibility:
      cases = {{"fog", 16, 16, 6, 256, 0},
               {"fog-lamp", 16, 12, 6, 256, 0},
               {"door-ajar", 16, 12, 8, 2048, 0, 2},
               {"many-lights", 15, 10, 6, 1024, 0, 2}};
      break;
  }
  for (const BundledCase& c : cases) expectBundledAgreement(c, name, configure, seedSalt);
}

}  // namespace pathlab::test
