// The variance maps (issue 34) against a brute-force estimate: each technique's variance of one
// pass's estimate, from one session's second moments over many passes, agrees with the spread
// of the same technique's image over as many independent one-pass sessions (other seeds), summed
// over the pixels, within the brute force's standard error (from the spread of the sessions'
// sums, which holds the correlation of one pass's splats across pixels). Camera-side techniques,
// light-tracing splats and a merge; and the dominant variance map names the technique with the
// most variance.
#include "core/render/render_session.h"
#include "core/render/technique_luminance.h"
#include "core/sampling/technique_label.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace pathlab {
namespace {

RenderSettings varianceSettings(const std::string& integrator) {
  RenderSettings s;
  s.width = s.height = 10;
  s.maxLength = 3;
  s.pyramidLength = 3;
  s.varianceMaps = true;
  s.integrator = IntegratorKind::Bpt;
  if (integrator == "vcm") {
    s.techniques = TechniqueSet::parse("all;m=all");
    s.mergeRadius = 0.05f;
    s.mergeRadiusAlpha = 1.f;  // a fixed radius: every pass the same distribution
  }
  return s;
}

void expectVarianceMatchesBruteForce(const Scene& scene, const RenderSettings& base, const std::vector<Technique>& xs) {
  constexpr int kPasses = 400;
  RenderSettings s = base;
  s.seed = 1;
  RenderSession session(scene, s);
  for (int i = 0; i < kPasses; ++i) session.renderPass();
  // Brute force: kPasses sessions of one pass each, their pass estimates X per pixel.
  const size_t P = static_cast<size_t>(s.width) * static_cast<size_t>(s.height);
  std::vector<std::vector<std::vector<double>>> X(xs.size(), std::vector<std::vector<double>>(kPasses));
  for (int i = 0; i < kPasses; ++i) {
    RenderSettings one = base;
    one.seed = 1000 + static_cast<uint64_t>(i);
    RenderSession single(scene, one);
    single.renderPass();
    for (size_t j = 0; j < xs.size(); ++j) {
      const Image img = single.techniqueImage(xs[j], false);
      X[j][static_cast<size_t>(i)].resize(P);
      for (size_t p = 0; p < P; ++p)
        X[j][static_cast<size_t>(i)][p] = luminance(Spectrum(img.rgb[3 * p], img.rgb[3 * p + 1], img.rgb[3 * p + 2]));
    }
  }
  for (size_t j = 0; j < xs.size(); ++j) {
    const std::vector<float> map = session.techniqueVariance(xs[j]);
    double mapSum = 0.0;
    for (const float v : map) mapSum += v;
    // Y_i = n / (n - 1) sum_p (X_ip - mean_p)^2: their mean is the brute force's sum of the
    // pixels' variances, their spread its standard error.
    std::vector<double> mean(P, 0.0), Y(kPasses, 0.0);
    for (const std::vector<double>& x : X[j])
      for (size_t p = 0; p < P; ++p) mean[p] += x[p] / kPasses;
    for (int i = 0; i < kPasses; ++i)
      for (size_t p = 0; p < P; ++p) {
        const double d = X[j][static_cast<size_t>(i)][p] - mean[p];
        Y[static_cast<size_t>(i)] += d * d * kPasses / (kPasses - 1.0);
      }
    double ySum = 0.0, ySum2 = 0.0;
    for (const double y : Y) ySum += y, ySum2 += y * y;
    const double brute = ySum / kPasses;
    const double se = std::sqrt(std::max(0.0, ySum2 / kPasses - brute * brute) / kPasses);
    ASSERT_GT(brute, 0.0) << techniqueLabel(xs[j]);
    // The map's own error is the brute force's (the same number of passes of the same estimate).
    const double z = (mapSum - brute) / (std::sqrt(2.0) * se);
    EXPECT_LT(std::abs(z), test::kMaxZ) << techniqueLabel(xs[j]) << ": map " << mapSum << ", brute force " << brute
                                        << " +- " << se;
    EXPECT_LT(se, 0.25 * brute) << techniqueLabel(xs[j]);  // a test that can tell
  }
}

TEST(VarianceMaps, EachTechniqueAgreesWithIndependentPasses) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  expectVarianceMatchesBruteForce(scene, varianceSettings("bpt"),
                                  {Technique{0, 3}, Technique{1, 2}, Technique{2, 1}, Technique{0, 4}, Technique{3, 1}});
}

TEST(VarianceMaps, AMergeAgreesWithIndependentPasses) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  expectVarianceMatchesBruteForce(scene, varianceSettings("vcm"), {Technique::merge(2, 2), Technique{1, 3}});
}

// Where one technique's variance is all of the techniques': (1,1) renders the light seen through
// the lens alone when the camera's own (0,2) is switched off.
TEST(VarianceMaps, TheDominantVarianceMapNamesTheNoisiestTechnique) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  RenderSettings s = varianceSettings("bpt");
  s.width = s.height = 24;
  RenderSession session(scene, s);
  for (int i = 0; i < 32; ++i) session.renderPass();
  const TechniqueLuminance v = techniqueLuminance(session);
  ASSERT_EQ(v.length, 3);
  ASSERT_EQ(v.variance.size(), v.weighted.size());
  const DominantMap m = dominantVarianceMap(v);
  int named = 0;
  for (size_t p = 0; p < m.technique.size(); ++p) {
    if (m.technique[p] < 0) continue;
    float most = 0.f;
    size_t which = 0;
    for (const Technique x : techniquesUpTo(3))
      if (v.variance[x.index()][p] > most) most = v.variance[x.index()][p], which = x.index();
    EXPECT_EQ(static_cast<size_t>(m.technique[p]), which) << p;
    ++named;
  }
  EXPECT_GT(named, 400);
}

}  // namespace
}  // namespace pathlab
