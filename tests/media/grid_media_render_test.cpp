// Heterogeneous media in every estimator (issue 35): a density grid of one everywhere renders the
// homogeneous fog it scales, in the path tracer, light tracing, BPT and VCM; and in a fog whose
// density rises with height, and in the bundled smoke scene, the estimators agree with each other
// (delta tracking on the walks, ratio tracking on every connection), subsets and unweighted BPT
// included. Region means with measured standard errors (tests/support/region_estimate.h).
#include "core/io/vdb_file.h"
#include "core/media/procedural_volumes.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/agreement.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace pathlab {
namespace {

namespace fs = std::filesystem;

// tests/scenes/grid-fog-KIND.gltf copied into a directory of the test's own, beside the .vdb it
// names (written here: pathlab's tests never write into the source tree).
Scene gridFogScene(const std::string& kind) {
  const fs::path dir = fs::temp_directory_path() / ("pathlab-grid-media-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path gltf = dir / ("grid-fog-" + kind + ".gltf");
  fs::copy_file(fs::path(PATHLAB_SOURCE_DIR) / "tests/scenes" / gltf.filename(), gltf, fs::copy_options::overwrite_existing);
  ProceduralVolume v{};
  if (parseProceduralVolume(kind, v)) {
    const int n = 16;
    writeDensityVdb((dir / (kind + ".vdb")).string(), "density", makeProceduralVolume(v, n, 1.f), proceduralVoxelSize(n),
                    proceduralOrigin(n));
  }
  SceneDesc desc = loadGltf(gltf.string());
  fs::remove_all(dir);
  return Scene(std::move(desc));
}

RenderSettings fogSettings() {
  RenderSettings s;
  s.width = 12, s.height = 12, s.maxLength = 4;
  return s;
}

TEST(GridMediaRender, ConstantDensityGridIsTheHomogeneousFog) {
  const Scene homogeneous = gridFogScene("homogeneous");
  const Scene constant = gridFogScene("constant");
  ASSERT_TRUE(constant.hasMedia());
  ASSERT_EQ(constant.media().media().size(), 1u);
  ASSERT_NE(constant.mediumGrid(0), nullptr);
  ASSERT_EQ(homogeneous.mediumGrid(0), nullptr);
  const RenderSettings base = fogSettings();
  const test::PixelLabels grid = test::gridLabels(base.width, base.height, 3, 3);
  const uint64_t seed = 1000 * test::testSeedBase() + 500;
  struct Case {
    const char* name;
    IntegratorKind kind;
    int passes;
    bool merges = false;
  };
  const Case cases[] = {{"pt", IntegratorKind::Pt, 1024},
                        {"lt", IntegratorKind::Lt, 4096},
                        {"bpt", IntegratorKind::Bpt, 384},
                        {"vcm", IntegratorKind::Bpt, 384, true}};
  std::vector<std::pair<std::string, test::Agreement>> results;
  int comparisons = 0;
  for (const Case& c : cases) {
    RenderSettings s = base;
    s.integrator = c.kind;
    if (c.merges) {
      s.techniques = TechniqueSet::parse("all;m=all");
      s.mergeRadius = 0.02f;
      s.mergeRadiusAlpha = 1.f;
    }
    s.seed = seed + 2 * uint64_t(&c - cases);
    const test::RegionMeans a = test::renderRegionMeans(homogeneous, s, c.passes, grid);
    s.seed += 1;
    const test::RegionMeans b = test::renderRegionMeans(constant, s, c.passes, grid);
    EXPECT_EQ(a.discarded + b.discarded, 0u) << c.name;
    const test::Agreement agreement = test::compareRegions(a, b);
    comparisons += agreement.comparisons;
    results.emplace_back(c.name, agreement);
    // Power: the whole image's standard error small against its mean.
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_LT(a.whole[size_t(ch)].standardError, 0.03 * a.whole[size_t(ch)].mean) << c.name << " channel " << ch;
  }
  const double threshold = test::bonferroniZ(test::kFamilyAlpha, comparisons);
  for (const auto& [name, agreement] : results) {
    std::cout << "constant grid vs homogeneous, " << name << ": max |z| " << agreement.maxAbsZ << " (" << agreement.worst
              << "), threshold " << threshold << "\n";
    EXPECT_LT(agreement.maxAbsZ, threshold) << name << ": " << agreement.worst;
  }
}

TEST(GridMediaRender, PtLtAndBptAgreeInARampFog) {
  const Scene scene = gridFogScene("ramp");
  ASSERT_NE(scene.mediumGrid(0), nullptr);
  const RenderSettings base = fogSettings();
  const uint64_t seed = 1000 * test::testSeedBase() + 600;
  test::EstimatorSpec subset =
      test::estimatorSpec("bpt subset, unweighted", base, IntegratorKind::Bpt, MisHeuristic::Off, seed + 4, 1024);
  // Without s = 0 and t = 1: (1, t) and (s, 2 <= t) cover every path of up to four edges.
  subset.settings.techniques = TechniqueSet::parse("t=2;t=3;t=4;1,2;1,3;1,4");
  const std::vector<test::EstimatorSpec> estimators = {
      test::estimatorSpec("pt", base, IntegratorKind::Pt, MisHeuristic::Power, seed + 1, 1024),
      test::estimatorSpec("lt", base, IntegratorKind::Lt, MisHeuristic::Balance, seed + 2, 8192),
      test::estimatorSpec("bpt", base, IntegratorKind::Bpt, MisHeuristic::Balance, seed + 3, 192), subset};
  const test::PixelLabels grid = test::gridLabels(base.width, base.height, 3, 3);
  const auto run = test::runAgreement(scene, estimators, {grid},
                                      // Light tracing converges slowly with the camera inside the fog.
                                      {{"pt", "bpt"},
                                       {"lt", "bpt", 0, 0.1},
                                       {"pt", "lt", 0, 0.1},
                                       {"bpt subset, unweighted", "bpt"}},
                                      test::kFamilyAlpha);
  test::report(run, "ramp fog");
  test::expectAgreement(run, "ramp fog");
}

TEST(GridMediaRender, PtAndBptAgreeOnTheSmokeScene) {
  const Scene scene = test::bundledScene("smoke");
  ASSERT_NE(scene.mediumGrid(0), nullptr);
  RenderSettings base;
  base.width = 12, base.height = 12, base.maxLength = 4;
  const uint64_t seed = 1000 * test::testSeedBase() + 700;
  const std::vector<test::EstimatorSpec> estimators = {
      test::estimatorSpec("pt", base, IntegratorKind::Pt, MisHeuristic::Power, seed + 1, 256),
      test::estimatorSpec("bpt", base, IntegratorKind::Bpt, MisHeuristic::Balance, seed + 2, 128),
      test::estimatorSpec("lt", base, IntegratorKind::Lt, MisHeuristic::Balance, seed + 3, 256)};
  // The path tracer cannot see the panel's own pixels as light tracing does (and the point light
  // is off-screen): pixels that see an emitter are left out.
  const test::PixelLabels grid = test::withoutSeenDirectly(scene, base, test::gridLabels(12, 12, 3, 3), test::isEmissive);
  const auto run = test::runAgreement(scene, estimators, {grid}, {{"pt", "bpt"}, {"lt", "bpt"}}, test::kFamilyAlpha);
  test::report(run, "smoke");
  test::expectAgreement(run, "smoke");
}

}  // namespace
}  // namespace pathlab
