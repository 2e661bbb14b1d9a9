// `pathlab converge` machinery: configuration parsing, the converge loop on a tiny render, CSV,
// efficiency table and the SVG plot.
#include "core/converge/convergence.h"
#include "core/converge/convergence_config.h"
#include "core/converge/convergence_report.h"
#include "core/converge/reference_key.h"
#include "core/metrics/loglog_plot.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

namespace pathlab {
namespace {

const std::string kBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

TEST(ConvergenceConfig, ParsesTheIssueExample) {
  const auto c = parseConvergenceConfigs("bpt;pt;lt;bpt:mis=power;bpt:mis=uniform", RenderSettings{});
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c[0].settings.integrator, IntegratorKind::Bpt);
  EXPECT_EQ(c[1].settings.integrator, IntegratorKind::Pt);
  EXPECT_EQ(c[2].settings.integrator, IntegratorKind::Lt);
  EXPECT_EQ(c[3].settings.mis.heuristic, MisHeuristic::Power);
  EXPECT_EQ(c[4].settings.mis.heuristic, MisHeuristic::Uniform);
  EXPECT_EQ(c[3].label, "bpt:mis=power");
}

TEST(ConvergenceConfig, TechniqueSpecsKeepTheirSeparators) {
  RenderSettings base;
  base.seed = 7;
  const auto c = parseConvergenceConfigs(" bpt:techniques=1,2;k=1,mis=power,beta=3 ; pt:max-length=4;", base);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].settings.techniques, TechniqueSet::parse("1,2;k=1"));
  EXPECT_EQ(c[0].settings.mis.heuristic, MisHeuristic::Power);
  EXPECT_EQ(c[0].settings.mis.beta, 3.f);
  EXPECT_EQ(c[0].settings.seed, 7u);
  EXPECT_EQ(c[1].settings.maxLength, 4);
  const auto d = parseConvergenceConfigs("bpt:techniques=s=1;t=1;k=1;lt", base);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].settings.techniques, TechniqueSet::parse("s=1;t=1;k=1"));
}

TEST(ConvergenceConfig, BadConfigsAreOneLineErrors) {
  for (const char* bad : {"", ";", "magic", "bpt:mis=max", "pt:mis=power", "bpt:beta=x", "bpt:foo=1", "bpt:mis",
                          "bpt:techniques=9,9,max-length=4", "bpt:max-length=0", "bpt;bpt", "bpt:techniques=x"}) {
    try {
      parseConvergenceConfigs(bad, RenderSettings{});
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
      EXPECT_EQ(msg.rfind("--configs:", 0), 0u) << msg;
    }
  }
}

// A number too large for its type is named as an overflow, not as "not a number".
TEST(ConvergenceConfig, OverflowIsNamedAsSuch) {
  try {
    parseConvergenceConfigs("bpt:mis=power,beta=1e999", RenderSettings{});
    ADD_FAILURE() << "accepted beta=1e999";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("beta=1e999 is out of range"), std::string::npos) << e.what();
  }
}

TEST(ReferenceKey, ChangesWithSettingsAndBudget) {
  RenderSettings s;
  const std::string a = referenceKey(kBox, s, "time=10");
  EXPECT_EQ(a.size(), 16u);
  EXPECT_EQ(a, referenceKey(kBox, s, "time=10"));
  EXPECT_NE(a, referenceKey(kBox, s, "time=20"));
  s.maxLength = 4;
  EXPECT_NE(a, referenceKey(kBox, s, "time=10"));
  EXPECT_THROW(referenceKey(kBox + ".missing", s, "time=10"), std::runtime_error);
}

// A .gltf whose buffer and image live in files of their own: changing either changes the key,
// restoring it restores the key, and where the scene lies does not matter.
TEST(ReferenceKey, HashesExternalBuffersAndImages) {
  const std::filesystem::path dir = std::filesystem::path(PATHLAB_TEST_TMP) / "reference_key";
  std::filesystem::create_directories(dir / "moved");
  const std::string gltf = R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "tri%20angle.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "images": [{"uri": "albedo.png"}], "textures": [{"source": 0}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}, "emissiveFactor": [1, 1, 1]}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
  const float triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  auto write = [](const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  };
  std::string bin(reinterpret_cast<const char*>(triangle), sizeof triangle);
  for (const auto& d : {dir, dir / "moved"}) {
    write(d / "scene.gltf", gltf);
    write(d / "tri angle.bin", bin);  // the URI is percent-encoded, as the loader decodes it
    write(d / "albedo.png", "not decoded, only hashed");
  }
  const std::string scene = (dir / "scene.gltf").string();
  const RenderSettings s;
  const std::string a = referenceKey(scene, s, "spp=8");
  EXPECT_EQ(a, referenceKey((dir / "moved" / "scene.gltf").string(), s, "spp=8"));

  std::string changed = bin;
  changed[4] ^= 1;  // same size: tinygltf checks byteLength
  write(dir / "tri angle.bin", changed);
  const std::string b = referenceKey(scene, s, "spp=8");
  EXPECT_NE(a, b);
  write(dir / "tri angle.bin", bin);
  EXPECT_EQ(a, referenceKey(scene, s, "spp=8"));

  write(dir / "albedo.png", "another image");
  EXPECT_NE(a, referenceKey(scene, s, "spp=8"));
  write(dir / "albedo.png", "not decoded, only hashed");

  std::filesystem::remove(dir / "tri angle.bin");
  EXPECT_THROW(referenceKey(scene, s, "spp=8"), std::runtime_error);
}

TEST(Convergence, ErrorFallsAndCheckpointsAreGeometric) {
  Scene scene(loadGltf(kBox));
  RenderSettings base;
  base.width = base.height = 12;
  base.maxLength = 4;
  auto configs = parseConvergenceConfigs("bpt;pt", base);
  ConvergenceConfig refConfig{"ref", base};
  refConfig.settings.integrator = IntegratorKind::Bpt;
  refConfig.settings.seed = 1000;
  ConvergenceBudget refBudget;
  refBudget.spp = 256;
  const Image reference = runConvergence(scene, refConfig, nullptr, refBudget).image;

  ConvergenceBudget budget;
  budget.spp = 40;
  std::vector<ConvergenceCurve> curves;
  for (const auto& c : configs) curves.push_back(runConvergence(scene, c, &reference, budget));
  for (const ConvergenceCurve& curve : curves) {
    std::vector<uint64_t> spp;
    for (const Checkpoint& c : curve.checkpoints) spp.push_back(c.spp);
    EXPECT_EQ(spp, (std::vector<uint64_t>{1, 2, 3, 5, 8, 12, 18, 27, 40})) << curve.label;
    const Checkpoint &first = curve.checkpoints.front(), &last = curve.checkpoints.back();
    ASSERT_TRUE(first.error && last.error);
    EXPECT_LT(last.error->relMse, 0.5 * first.error->relMse) << curve.label;
    EXPECT_GT(last.twoBuffer.relMse, 0.0);
    EXPECT_EQ(last.cameraSamples, 40u * 144u);
    for (size_t i = 1; i < curve.checkpoints.size(); ++i)
      EXPECT_GE(curve.checkpoints[i].seconds, curve.checkpoints[i - 1].seconds);
  }

  const std::string csv = convergenceCsv(curves);
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 2 * 9);
  EXPECT_EQ(csv.rfind("config,spp,seconds,rmse,relmse,mape,", 0), 0u);
  const auto rows = efficiencyRows(curves);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].speedup, 1.0);
  EXPECT_DOUBLE_EQ(rows[1].efficiency, 1.0 / (rows[1].relMse * rows[1].seconds));
  const std::string md = efficiencyMarkdown(rows);
  EXPECT_EQ(std::count(md.begin(), md.end(), '\n'), 4);
}

// Metropolis's passes continue the same chains: the two-buffer estimate (which assumes independent
// passes) and the bias^2 / variance split are left out (NaN, no split), in the CSV as empty fields
// and in the table as "–"; the error against the reference stays.
TEST(Convergence, MetropolisHasNoTwoBufferEstimate) {
  Scene scene(loadGltf(kBox));
  RenderSettings base;
  base.width = base.height = 8;
  base.maxLength = 3;
  const auto configs = parseConvergenceConfigs("mlt:bootstrap=500,chains=16;bpt", base);
  ConvergenceBudget budget;
  budget.spp = 4;
  const Image reference = runConvergence(scene, configs[1], nullptr, budget).image;
  const std::vector<ConvergenceCurve> curves{runConvergence(scene, configs[0], &reference, budget),
                                             runConvergence(scene, configs[1], &reference, budget)};
  const Checkpoint& mlt = curves[0].checkpoints.back();
  ASSERT_TRUE(mlt.error.has_value());
  EXPECT_TRUE(std::isnan(mlt.twoBuffer.relMse) && std::isnan(mlt.twoBuffer.mse));
  EXPECT_FALSE(mlt.split.has_value());
  EXPECT_TRUE(std::isfinite(curves[1].checkpoints.back().twoBuffer.relMse));
  const std::string csv = convergenceCsv(curves);
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
  const std::string md = efficiencyMarkdown(efficiencyRows(curves));
  EXPECT_NE(md.find("| – |"), std::string::npos) << md;
}

TEST(Convergence, ATimeBudgetRunsAtLeastTwoPasses) {
  Scene scene(loadGltf(kBox));
  RenderSettings base;
  base.width = base.height = 4;
  ConvergenceBudget budget;
  budget.seconds = 1e-6;
  const ConvergenceCurve curve = runConvergence(scene, {"pt", base}, nullptr, budget);
  EXPECT_EQ(curve.checkpoints.back().spp, 2u);
  EXPECT_FALSE(curve.checkpoints.back().error.has_value());
}

TEST(Convergence, TheCpuClockIsRecordedAndCanSetTheBudget) {
  Scene scene(loadGltf(kBox));
  RenderSettings base;
  base.width = base.height = 8;
  ConvergenceBudget budget;
  budget.seconds = 0.05;
  budget.clock = ClockKind::Cpu;
  const ConvergenceCurve curve = runConvergence(scene, {"pt", base}, nullptr, budget);
  const Checkpoint& last = curve.checkpoints.back();
  EXPECT_EQ(last.seconds, last.cpuSeconds);
  EXPECT_GE(last.cpuSeconds, 0.05);
  EXPECT_GT(last.wallSeconds, 0.0);
}

TEST(LogLogPlot, OnePolylinePerSeriesAndDecadeLabels) {
  LogLogPlot plot{"title & <escaping>", "time (s)", "relMSE", {}};
  plot.series.push_back({"bpt", {{0.01, 1.0}, {0.1, 0.1}, {1.0, 1e-4}}});
  plot.series.push_back({"bpt:techniques=1,2;k=1", {{0.02, 2.0}, {2.0, 0.02}, {3.0, 0.0}}});
  const std::string svg = renderSvg(plot);
  EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  size_t polylines = 0;
  for (size_t at = svg.find("<polyline"); at != std::string::npos; at = svg.find("<polyline", at + 1)) ++polylines;
  EXPECT_EQ(polylines, 2u);
  EXPECT_NE(svg.find("title &amp; &lt;escaping&gt;"), std::string::npos);
  EXPECT_NE(svg.find(">0.01</text>"), std::string::npos);  // an x decade label
  EXPECT_NE(svg.find(">-4</tspan>"), std::string::npos);   // a y decade label, 10^-4
  EXPECT_THROW(renderSvg(LogLogPlot{}), std::invalid_argument);
}

}  // namespace
}  // namespace pathlab
