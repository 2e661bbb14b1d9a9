// Agreement between the bidirectional techniques on scenes without delta components (Lambertian
// surfaces, one area light, a pinhole camera), where every technique (s, t) can sample every path
// of its length s + t - 1 (Veach 1997, sec. 10.2). Hence:
//   - every unweighted technique of length k is an unbiased estimate of the same image, the light
//     carried by paths of exactly k edges;
//   - the MIS-weighted shares of the techniques of length k sum to that image (the weights of a
//     path sum to one over the enabled techniques, Veach eq. 9.2 / 10.9);
//   - that image is what the path tracer adds when its maximum length goes from k - 1 to k;
//   - any enabled subset that has at least one technique of every length gives the full image.
// Exact identities are checked on the same samples (the technique pyramid, isolation and the
// technique set share their connection streams); the rest by z-tests with measured standard
// errors and a Bonferroni threshold (tests/support/agreement.h). Fixed seeds.
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"
#include "tests/support/bpt_scenes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace pathlab {
namespace {

using test::PixelLabels;
using test::RegionMeans;

using test::kFamilyAlpha;
constexpr int kAgreementSize = 16;

// The bundled Cornell box with its light 3 x 3 times larger (same power, Le / 9), so that the
// path tracer's hits of the light (at length 1 a coin flip in every pixel the light partly
// covers) reach a standard error of a few percent within a test's budget. Everything else is the
// bundled scene.
const Scene& scaledCornellBox() {
  static const Scene scene = [] {
    SceneDesc desc = loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf");
    const float f = 3.f;
    for (TriangleMesh& mesh : desc.meshes) {
      if (!desc.materials[static_cast<size_t>(mesh.material)].isEmissive()) continue;
      Vec3 centre(0.f);
      for (const Vec3& p : mesh.positions) centre += p / static_cast<float>(mesh.positions.size());
      for (Vec3& p : mesh.positions) p = Vec3(centre.x + f * (p.x - centre.x), p.y, centre.z + f * (p.z - centre.z));
      desc.materials[static_cast<size_t>(mesh.material)].emissiveStrength /= f * f;
    }
    return Scene(std::move(desc));
  }();
  return scene;
}

RenderSettings bpt(int maxLength, uint64_t seed, const std::string& techniques = "all",
                   MisHeuristic h = MisHeuristic::Balance) {
  RenderSettings s;
  s.width = s.height = kAgreementSize;
  s.maxLength = maxLength;
  s.integrator = IntegratorKind::Bpt;
  s.techniques = TechniqueSet::parse(techniques);
  s.mis.heuristic = h;
  s.seed = 1000 * test::testSeedBase() + seed;
  return s;
}

// A Lambertian sphere inside an integrating sphere (bpt_scenes.h): no concave edge, so every
// unweighted technique has finite variance and can be z-tested.
const Scene& integratingSphere() {
  static const Scene scene(test::integratingSphere());
  return scene;
}

std::string technique(int s, int t) { return std::to_string(s) + "," + std::to_string(t); }

Image sumImages(const std::vector<Image>& images) {
  Image sum = images.front();
  for (size_t k = 1; k < images.size(); ++k)
    for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += images[k].rgb[i];
  return sum;
}

// Largest |a - b| relative to the largest |b|.
double relativeDifference(const Image& a, const Image& b) {
  double diff = 0.0, scale = 0.0;
  for (size_t i = 0; i < a.rgb.size(); ++i) {
    diff = std::max(diff, std::abs(static_cast<double>(a.rgb[i]) - static_cast<double>(b.rgb[i])));
    scale = std::max(scale, std::abs(static_cast<double>(b.rgb[i])));
  }
  return scale > 0.0 ? diff / scale : diff;
}

// The weighted shares of length k from the pyramid, summed.
Image lengthImage(const RenderSession& session, int k) {
  std::vector<Image> shares;
  for (const Technique x : techniquesOfLength(k)) shares.push_back(session.techniqueImage(x, false));
  return sumImages(shares);
}

// Same samples: the weighted pyramid buffers sum to the image, the disabled techniques' weighted
// buffers are black, and each unweighted buffer is exactly what the technique renders alone
// (techniques = "s,t") and what isolating it unweighted renders (connection streams are keyed by
// sample and (s, t), so all three see the same connections).
TEST(TechniqueAgreement, PyramidIsolationAndTechniqueSetsAreTheSameEstimates) {
  const Scene& scene = scaledCornellBox();
  const int K = 4, passes = 4;
  const std::string enabled = "s=0;1,2;2,2;3,1;k=4";  // a covering subset, to see disabled shares too
  RenderSettings s = bpt(K, 3, enabled, MisHeuristic::Power);
  s.pyramidLength = K;
  RenderSession session(scene, s);
  for (int i = 0; i < passes; ++i) session.renderPass();
  ASSERT_TRUE(session.hasPyramid());
  const TechniqueSet set = TechniqueSet::parse(enabled);

  std::vector<Image> shares;
  for (const Technique x : techniquesUpTo(K)) {
    const Image weighted = session.techniqueImage(x, false);
    if (!set.contains(x)) {
      EXPECT_EQ(*std::max_element(weighted.rgb.begin(), weighted.rgb.end()), 0.f) << technique(x.s, x.t);
    }
    shares.push_back(weighted);
  }
  EXPECT_LT(relativeDifference(sumImages(shares), session.image()), 1e-5);

  for (const auto& [sl, t] : std::vector<std::pair<int, int>>{{0, 3}, {1, 2}, {2, 1}, {1, 3}, {3, 2}, {4, 1}}) {
    const Image unweighted = session.techniqueImage({sl, t}, true);
    ASSERT_GT(*std::max_element(unweighted.rgb.begin(), unweighted.rgb.end()), 0.f) << technique(sl, t);
    RenderSettings alone = bpt(K, 3, technique(sl, t));
    RenderSession aloneSession(scene, alone);
    RenderSettings isolated = bpt(K, 3, enabled, MisHeuristic::Power);
    isolated.isolate = Isolation{sl, t, true};
    RenderSession isolatedSession(scene, isolated);
    RenderSettings share = isolated;
    share.isolate = Isolation{sl, t, false};
    RenderSession shareSession(scene, share);
    for (int i = 0; i < passes; ++i) {
      aloneSession.renderPass();
      isolatedSession.renderPass();
      shareSession.renderPass();
    }
    EXPECT_LT(relativeDifference(aloneSession.image(), unweighted), 1e-5) << technique(sl, t);
    EXPECT_LT(relativeDifference(isolatedSession.image(), unweighted), 1e-5) << technique(sl, t);
    EXPECT_LT(relativeDifference(shareSession.image(), session.techniqueImage({sl, t}, false)), 1e-5) << technique(sl, t);
  }
}

// Every unweighted technique of length k against the sum of the weighted shares of length k, from
// the same samples: the per-pass difference is a paired sample, so its spread is the standard
// error of the difference itself. Lengths 1 to 4, all 14 techniques, in the integrating sphere:
// in the Cornell box the unweighted connections (s, t >= 2) have infinite variance near its edges and
// corners (the geometry term's 1 / d^2), so their sample means converge too slowly for a z-test
// and fail it now and then whatever the seed. The unweighted s = 0 techniques are the noisiest
// here (hits of the light after k - 1 bounces): 2 x 2 regions of 64 pixels and enough passes
// for a few hundred hits in each (the power check below guards against too few: a z-test on a
// Poisson count of a handful is meaningless).
TEST(TechniqueAgreement, UnweightedTechniquesOfOneLengthAgree) {
  const Scene& scene = integratingSphere();
  const int K = 4;
  RenderSettings s = bpt(K, 41);
  s.pyramidLength = K;
  const PixelLabels grid = test::gridLabels(kAgreementSize, kAgreementSize, 2, 2);
  std::vector<test::ImageOf> images;
  std::vector<std::pair<int, int>> techniques;
  for (const Technique x : techniquesUpTo(K)) {
    images.push_back([=](const RenderSession& r) {
      return test::imageDifference(r.techniqueImage(x, true), lengthImage(r, x.length()));
    });
    techniques.emplace_back(x.s, x.t);
  }
  for (int k = 1; k <= K; ++k) images.push_back([=](const RenderSession& r) { return lengthImage(r, k); });
  const auto means = test::renderRegionMeans(scene, s, 256, {grid}, images);
  int comparisons = 0;
  std::vector<test::Agreement> results;
  for (size_t i = 0; i < techniques.size(); ++i) {
    results.push_back(test::testZero(means[i].front()));
    comparisons += results.back().comparisons;
  }
  const double threshold = test::bonferroniZ(kFamilyAlpha, comparisons);
  std::cout << comparisons << " comparisons, threshold " << threshold << "\n";
  for (size_t i = 0; i < techniques.size(); ++i) {
    const auto [sl, t] = techniques[i];
    const RegionMeans& length = means[techniques.size() + static_cast<size_t>(sl + t - 2)].front();
    // Power: the median over regions and channels of the difference's standard error relative
    // to the length's image.
    std::vector<double> relative;
    for (size_t r = 0; r < length.region.size(); ++r)
      for (size_t c = 0; c < 3; ++c)
        relative.push_back(means[i].front().region[r][c].standardError / length.region[r][c].mean);
    std::nth_element(relative.begin(), relative.begin() + static_cast<std::ptrdiff_t>(relative.size() / 2),
                     relative.end());
    const double power = relative[relative.size() / 2];
    std::cout << "  unweighted (" << technique(sl, t) << ") - length image: max |z| " << results[i].maxAbsZ
              << ", median relative se " << power << "\n";
    EXPECT_LT(results[i].maxAbsZ, threshold) << "(" << technique(sl, t) << "): " << results[i].worst;
    // 10 %: at least ~100 independent events per region, so that the normal approximation
    // behind the z-test holds even for the hits of the unweighted s = 0 techniques.
    EXPECT_LT(power, 0.10) << "(" << technique(sl, t) << ") too noisy to detect a bias";
  }
}

// The image of each length k (weighted shares of length k from the pyramid) against the path
// tracer's image at maximum length k minus that at k - 1. The two path tracer renders share their
// seed and run in lockstep, so their per-pass difference is a paired sample of the path tracer's
// estimate of length k alone, with its own standard error (the paths of the two coincide up to
// k - 1 edges, and that shared part cancels).
TEST(TechniqueAgreement, EachLengthMatchesThePathTracer) {
  const Scene& scene = scaledCornellBox();
  const int K = 4;
  RenderSettings s = bpt(K, 51);
  s.pyramidLength = K;
  const PixelLabels grid = test::gridLabels(kAgreementSize, kAgreementSize, 4, 4);
  std::vector<test::ImageOf> images;
  for (int k = 1; k <= K; ++k) images.push_back([=](const RenderSession& r) { return lengthImage(r, k); });
  const auto bptLengths = test::renderRegionMeans(scene, s, 192, {grid}, images);

  std::vector<test::Agreement> results;
  int comparisons = 0;
  for (int k = 1; k <= K; ++k) {
    RenderSettings p = s;
    p.integrator = IntegratorKind::Pt;
    p.pyramidLength = 0;
    p.maxLength = k;
    p.seed = 1000 * test::testSeedBase() + 61;
    RegionMeans ptLength;
    // 768 passes: roulette from the second scattering on (russian_roulette.h) ends some of the
    // length-3 and -4 paths, whose survivors carry 1/q, and 512 left the blue channel of length 4
    // at 2.06 % (seed 0) against the 2 % below.
    if (k == 1) {
      ptLength = test::renderRegionMeans(scene, p, 768, grid);
    } else {
      RenderSettings shorter = p;
      shorter.maxLength = k - 1;
      ptLength = test::renderPairedDifference(scene, p, shorter, 768, grid);
    }
    const RegionMeans& b = bptLengths[static_cast<size_t>(k - 1)].front();
    results.push_back(test::compareRegions(b, ptLength));
    comparisons += results.back().comparisons;
    // Power: the length's image is measured to a few percent.
    for (size_t c = 0; c < 3; ++c)
      EXPECT_LT(std::hypot(ptLength.whole[c].standardError, b.whole[c].standardError), 0.02 * b.whole[c].mean)
          << "length " << k << " channel " << c;
  }
  const double threshold = test::bonferroniZ(kFamilyAlpha, comparisons);
  for (int k = 1; k <= K; ++k) {
    const test::Agreement& r = results[static_cast<size_t>(k - 1)];
    std::cout << "length " << k << ": max |z| " << r.maxAbsZ << "; worst " << r.worst << "\n";
    EXPECT_LT(r.maxAbsZ, threshold) << "length " << k << ": " << r.worst;
  }
}

// Every estimator in the integrating sphere: PT, LT and BPT under the balance, power and uniform
// heuristics. This is where the uniform heuristic is tested without delta components: it gives
// every technique able to produce a path the weight 1/k whatever its density, so its variance is
// that of the unweighted techniques, finite only where no connection comes near a concave edge
// (bpt_agreement_test.cpp, CornellBox).
TEST(TechniqueAgreement, EveryEstimatorAgreesInTheIntegratingSphere) {
  const Scene& scene = integratingSphere();
  const int K = 6;
  const PixelLabels grid = test::gridLabels(kAgreementSize, kAgreementSize, 4, 4);
  RenderSettings pt = bpt(K, 81);
  pt.integrator = IntegratorKind::Pt;
  RenderSettings lt = bpt(K, 82);
  lt.integrator = IntegratorKind::Lt;
  const std::vector<test::EstimatorSpec> estimators = {{"pt", pt, 256},
                                                       {"balance", bpt(K, 83), 64},
                                                       {"power", bpt(K, 84, "all", MisHeuristic::Power), 64},
                                                       {"uniform", bpt(K, 85, "all", MisHeuristic::Uniform), 96},
                                                       {"lt", lt, 96}};
  const auto run = test::runAgreement(scene, estimators, {grid},
                                      {{"balance", "pt"},
                                       {"power", "pt"},
                                       {"uniform", "pt"},
                                       {"lt", "pt"},
                                       {"power", "balance"},
                                       {"uniform", "balance"},
                                       {"lt", "balance"}},
                                      kFamilyAlpha);
  std::cout << run.summary();
  test::expectAgreement(run, "integrating sphere");
}

// Subsets of techniques with at least one technique of every length give the full image under
// every heuristic (the weights are normalised over the enabled set). A subset that misses length 3
// must fail the same test: the negative control that shows the test can see a missing length.
// In the integrating sphere: a subset may hold a single unweighted connection of some length
// (e.g. t=2 has only (2,2) at length 3), which has infinite variance in a room.
TEST(TechniqueAgreement, CoveringSubsetsGiveTheFullImage) {
  const Scene& scene = integratingSphere();
  const int K = 4;
  const PixelLabels grid = test::gridLabels(kAgreementSize, kAgreementSize, 2, 2);
  std::vector<test::EstimatorSpec> estimators = {{"all", bpt(K, 71), 96}};
  std::vector<std::pair<std::string, MisHeuristic>> subsets = {
      {"s=0", MisHeuristic::Balance}, {"s=1", MisHeuristic::Power},       {"t=1", MisHeuristic::Uniform},
      {"t=2", MisHeuristic::Balance}, {"s=0;t=1", MisHeuristic::Uniform}, {"k=1;k=2;2,2;3,2", MisHeuristic::Power}};
  // Random covering subsets: each length gets a random non-empty set of its techniques.
  std::mt19937 rng(1234);
  for (int i = 0; i < 2; ++i) {
    std::string spec;
    for (int k = 1; k <= K; ++k) {
      std::vector<Technique> chosen;
      while (chosen.empty())
        for (const Technique x : techniquesOfLength(k))
          if (rng() % 2) chosen.push_back(x);
      for (const Technique x : chosen) spec += (spec.empty() ? "" : ";") + technique(x.s, x.t);
    }
    subsets.emplace_back(spec, static_cast<MisHeuristic>(i % 3));
  }
  std::vector<test::PairSpec> pairs;
  uint64_t seed = 72;
  for (const auto& [spec, h] : subsets) {
    // Without an s = 1 technique some lengths rest on hits of the light or on connections
    // alone, which are noisier: more passes.
    const TechniqueSet set = TechniqueSet::parse(spec);
    bool hasS1 = false;
    for (int t = 1; t <= K; ++t) hasS1 = hasS1 || set.contains(1, t);
    estimators.push_back({spec, bpt(K, seed++, spec, h), hasS1 ? 48 : 128});
    pairs.push_back({spec, "all", 0, 0.05});
  }
  estimators.push_back({"missing length 3", bpt(K, seed++, "k=1;k=2;k=4"), 48});
  const auto run = test::runAgreement(scene, estimators, {grid}, pairs, kFamilyAlpha);
  std::cout << run.summary();
  std::string times;
  for (double t : run.seconds) times += " " + std::to_string(t).substr(0, 5);
  std::cout << "seconds" << times << "\n";
  test::expectAgreement(run, "covering subsets");

  const test::Agreement missing = test::compareRegions(run.estimates.back(), run.estimates.front());
  EXPECT_GT(missing.maxAbsZ, 2.0 * run.threshold) << "a missing length must be visible: " << missing.worst;
  std::cout << "missing length 3 (must differ): " << missing.worst << "\n";
}

}  // namespace
}  // namespace pathlab
