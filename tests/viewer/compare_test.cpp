// The viewer's A/B comparison (issue 14): side B parsed from a converge CONFIG in side A's view,
// printed back canonically, swapped, laid out beside A; presets that set both sides; and end to
// end, a headless `view --compare` whose two halves each converge to a standalone render of their
// own configuration and not to the other's.
#include "ui/lane/compare.h"
#include "ui/presets/presets.h"

#include "core/film/image_io.h"
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <regex>

namespace pathlab::ui {
namespace {

namespace fs = std::filesystem;

RenderSettings sideA() {
  RenderSettings a;
  a.width = 320;
  a.height = 200;
  a.seed = 7;
  a.maxLength = 5;
  a.integrator = IntegratorKind::Bpt;
  a.techniques = TechniqueSet::parse("k=2");
  a.mis.heuristic = MisHeuristic::Power;
  a.pyramidLength = 3;
  a.checkTechniques = true;
  a.camera = lookAtCamera(Vec3(0.f, 1.f, 3.f), Vec3(0.f, 1.f, 0.f), 0.7f);
  return a;
}

TEST(Compare, SideBIsTheDefaultEstimatorChangedByItsConfigInSideAsView) {
  const RenderSettings a = sideA();
  const EstimatorState pt = compareEstimator("pt", a);
  EXPECT_EQ(pt.settings.integrator, IntegratorKind::Pt);
  EXPECT_EQ(pt.settings.maxLength, 5);  // A's, unless the CONFIG sets one
  const EstimatorState power = compareEstimator("bpt:mis=power,techniques=t=1,max-length=3", a);
  EXPECT_EQ(power.settings.mis.heuristic, MisHeuristic::Power);
  EXPECT_EQ(power.settings.techniques, TechniqueSet::lightTracing());
  EXPECT_EQ(power.settings.maxLength, 3);
  // Nothing of A's estimator leaks into B: the default set and heuristic, no pyramid, no check.
  const RenderSettings b = compareRenderSettings(compareEstimator("bpt", a), a);
  EXPECT_EQ(b.techniques, TechniqueSet::all());
  EXPECT_EQ(b.mis.heuristic, MisHeuristic::Balance);
  EXPECT_EQ(b.pyramidLength, 0);
  EXPECT_FALSE(b.checkTechniques);
  // ... and the whole view is A's.
  EXPECT_EQ(b.width, a.width);
  EXPECT_EQ(b.height, a.height);
  EXPECT_EQ(b.seed, a.seed);
  EXPECT_EQ(b.camera, a.camera);
  EXPECT_NO_THROW(validateSettings(b));
  // Bad CONFIGs: the parser's one line.
  EXPECT_THROW(compareEstimator("bpt:mis=nope", a), std::invalid_argument);
  EXPECT_THROW(compareEstimator("ppm", a), std::invalid_argument);  // vcm and bpm are configurations now
  EXPECT_THROW(compareEstimator("pt;bpt", a), std::invalid_argument);
}

TEST(Compare, ConfigTextParsesBackToTheSameEstimator) {
  const RenderSettings a = sideA();
  for (const char* config : {"pt", "lt", "bpt", "bpt:mis=power,beta=3", "bpt:mis=uniform,techniques=s=0;s=1",
                             "bpt:connect=endpoints,min-connection=0.05", "bpt:mis=off,max-length=4",
                             "bpt:techniques=1,2;2,1;k=4"}) {
    const RenderSettings first = compareEstimator(config, a).settings;
    const std::string text = configText(first);
    EXPECT_EQ(compareEstimator(text, a).settings, first) << config << " -> " << text;
  }
  EXPECT_EQ(configText(compareEstimator("pt", a).settings), "pt:max-length=5");
  EXPECT_EQ(configText(compareEstimator("bpt:mis=power", a).settings), "bpt:mis=power,max-length=5");
}

TEST(Compare, SwapExchangesTheEstimatorsAndShowsBsConfig) {
  const RenderSettings a = sideA();
  CompareState compare;
  ASSERT_TRUE(applyCompareConfig(compare, "pt", a));
  EXPECT_TRUE(compare.on);
  EstimatorState sideAState = EstimatorState::from(a);
  sideAState.mode = EstimatorMode::IsolateUnweighted;
  sideAState.isolated = {1, 2};
  swapSides(compare, sideAState);
  EXPECT_EQ(sideAState.settings.integrator, IntegratorKind::Pt);
  EXPECT_EQ(compare.b.mode, EstimatorMode::IsolateUnweighted);  // B keeps A's isolation
  EXPECT_EQ(compare.typed, "bpt:mis=power,techniques=k=2,max-length=5");
  // A refused CONFIG keeps B and says why.
  EXPECT_FALSE(applyCompareConfig(compare, "bpt:beta=1000", a));
  EXPECT_NE(compare.error.find("beta"), std::string::npos);
  EXPECT_EQ(compare.b.mode, EstimatorMode::IsolateUnweighted);
}

TEST(Compare, SplitRoomPutsTwoImagesOfTheAspectSideBySideOrStacked) {
  // A wide room: side by side, B right of A, same size, the camera's aspect.
  auto [a, b] = splitRoom(PixelRect{{100, 0}, {900, 400}}, 1.5f, 8);
  EXPECT_EQ(a.size, b.size);
  EXPECT_NEAR(static_cast<float>(a.size.x) / static_cast<float>(a.size.y), 1.5f, 0.02f);
  EXPECT_GE(b.origin.x, a.origin.x + a.size.x + 8);
  EXPECT_GE(a.origin.x, 100);
  EXPECT_LE(b.origin.x + b.size.x, 1000);
  // A tall room: one above the other.
  std::tie(a, b) = splitRoom(PixelRect{{0, 0}, {400, 900}}, 1.f, 8);
  EXPECT_EQ(a.size, b.size);
  EXPECT_GE(b.origin.y, a.origin.y + a.size.y + 8);
  EXPECT_EQ(a.size.x, 400);
  EXPECT_EQ(threadsPerSide(2), 1);
  EXPECT_EQ(threadsPerSide(1), 1);
  EXPECT_EQ(threadsPerSide(8), 4);
}

TEST(Compare, PresetsSetSideBAndRefuseABadOne) {
  const auto presets = parsePresets(
      R"({"presets": [{"name": "pt | bpt", "integrator": "pt", "compare": "bpt:mis=power"}, {"name": "plain"}]})", "p.json");
  ASSERT_TRUE(presets[0].compare.has_value());
  EXPECT_EQ(*presets[0].compare, "bpt:mis=power");
  EXPECT_FALSE(presets[1].compare.has_value());
  try {
    parsePresets(R"({"presets": [{"name": "x", "compare": "bpt:mis=nope"}]})", "p.json");
    FAIL() << "a bad CONFIG was accepted";
  } catch (const PresetError& e) {
    EXPECT_NE(std::string(e.what()).find("p.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("nope"), std::string::npos) << e.what();
  }
  // The shipped presets include comparisons, and each of their side Bs parses at its length.
  int comparisons = 0;
  for (const NamedPreset& p : loadPresets(std::string(PATHLAB_SOURCE_DIR) + "/assets/presets.json"))
    comparisons += p.compare ? 1 : 0;
  EXPECT_GE(comparisons, 3);
}

// End to end. Luminance of a pixel.
double lum(const Image& im, size_t i) { return (im.rgb[3 * i] + im.rgb[3 * i + 1] + im.rgb[3 * i + 2]) / 3.0; }

// The largest |z| over a 4 x 4 grid of blocks of the per-pixel difference x - y of two independent
// estimates: each block's mean difference over its standard error (the differences' own spread).
double maxBlockZ(const Image& x, const Image& y) {
  EXPECT_EQ(x.width, y.width);
  EXPECT_EQ(x.height, y.height);
  double worst = 0.0;
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      double s = 0.0, s2 = 0.0;
      int n = 0;
      for (int py = by * x.height / 4; py < (by + 1) * x.height / 4; ++py)
        for (int px = bx * x.width / 4; px < (bx + 1) * x.width / 4; ++px, ++n) {
          const size_t i = static_cast<size_t>(py) * static_cast<size_t>(x.width) + static_cast<size_t>(px);
          const double d = lum(x, i) - lum(y, i);
          s += d;
          s2 += d * d;
        }
      const double mean = s / n, var = std::max(s2 / n - mean * mean, 1e-30) * n / (n - 1);
      worst = std::max(worst, std::abs(mean) / std::sqrt(var / n));
    }
  return worst;
}

const std::string kCompareTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_compare";
const std::string kCompareBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

TEST(CompareHeadless, TwoLabelledHalvesEachConvergeToTheirOwnConfiguration) {
  // A: direct light only (length 2, techniques k=2); B: the path tracer (every length up to 3). They
  // differ by the indirect light, so each half must match its own configuration's render only.
  const std::string work = kCompareTmp + "/halves";
  fs::remove_all(work);
  fs::create_directories(work);
  const std::string shot = work + "/shot.png";
  const pathlab::test::CommandRun view = pathlab::test::runPathlab(
      work,
      "view " + kCompareBox + " --headless --width 800 --height 400 --hide-ui --render-scale 0.25 --threads 2 --max-length 3 "
      "--integrator bpt --techniques k=2 --compare pt --seed 3 --spp 24 --frames 10 "
      "--script '6:wait=24;8:key=Ctrl+S' --screenshot " + shot,
      "cd " + work + " &&");
  ASSERT_EQ(view.exitCode, 0) << view.err;
  // Both halves drawn, the same size, B right of A, both at the asked samples.
  const std::regex line(R"(image (\d+)x(\d+)\+(\d+)\+(\d+) at (\d+) spp, B image (\d+)x(\d+)\+(\d+)\+(\d+) at (\d+) spp)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(view.err, m, line)) << view.err;
  const int aw = std::stoi(m[1]), ah = std::stoi(m[2]), ax = std::stoi(m[3]);
  const int bw = std::stoi(m[6]), bh = std::stoi(m[7]), bx = std::stoi(m[8]);
  EXPECT_EQ(aw, bw);
  EXPECT_EQ(ah, bh);
  EXPECT_NEAR(aw, ah, 1);  // the Cornell box's square camera
  EXPECT_GE(bx, ax + aw);
  EXPECT_EQ(std::stoi(m[5]), 24);
  EXPECT_EQ(std::stoi(m[10]), 24);

  // Ctrl+S saved out/pathlab-STAMP.exr (A) and out/pathlab-STAMP-B.exr (B).
  std::string pathA, pathB;
  for (const auto& entry : fs::directory_iterator(work + "/out")) {
    const std::string p = entry.path().string();
    if (p.ends_with("-B.exr")) pathB = p;
    else if (p.ends_with(".exr")) pathA = p;
  }
  ASSERT_FALSE(pathA.empty() || pathB.empty()) << view.err;
  const Image a = readImage(pathA);
  const Image b = readImage(pathB);
  ASSERT_GT(a.width, 0);
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.height, b.height);
  // Each configuration rendered alone, at the same size with another seed (independent estimates).
  auto render = [&](const std::string& name, const std::string& flags) {
    const std::string out = work + "/" + name + ".exr";
    const pathlab::test::CommandRun r = pathlab::test::runPathlab(
        work, "render " + kCompareBox + " -o " + out + " --width " + std::to_string(a.width) + " --height " +
                  std::to_string(a.height) + " --max-length 3 --spp 48 --seed 11 --threads 2 --force " + flags);
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return readImage(out);
  };
  const Image directOnly = render("direct", "--integrator bpt --techniques k=2");
  const Image pathTraced = render("pt", "--integrator pt");
  // 16 blocks: |z| < 4.5 holds for a true match with probability above 0.9999 (Bonferroni).
  EXPECT_LT(maxBlockZ(a, directOnly), 4.5);
  EXPECT_LT(maxBlockZ(b, pathTraced), 4.5);
  // Each half against the other's configuration: the indirect light is far outside the noise.
  EXPECT_GT(maxBlockZ(a, pathTraced), 10.0);
  EXPECT_GT(maxBlockZ(b, directOnly), 10.0);
  // Both halves drawn: the captions' dark boxes and the images, not the window's background.
  const pathlab::test::Png png = pathlab::test::readPng(shot);
  ASSERT_GT(png.width, 0);
  EXPECT_GT(png.variance(ax, 0, ax + aw, ah), 1.0);
  EXPECT_GT(png.variance(bx, 0, bx + bw, bh), 1.0);
}

TEST(CompareHeadless, ABadConfigIsOneLineAndAnError) {
  const pathlab::test::CommandRun r =
      pathlab::test::runPathlab(kCompareTmp, "view " + kCompareBox + " --headless --frames 2 --compare 'bpt:mis=nope'");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("nope"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

}  // namespace
}  // namespace pathlab::ui
