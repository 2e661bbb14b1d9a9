// The path inspector end to end (issue 12): headless, K then a click on the Cornell box draws the
// picked sample's subpaths and connections over the image in their colours (camera subpath blue,
// light subpath orange, connections green), none without the click; N steps to the next sample and
// the drawing changes; the render is never restarted by it (the same samples per pixel arrive).
// The 3D view (O) draws the same sample from its own camera; orbiting it changes the view and not
// the render (the same generation); Ctrl+J and Ctrl+E write the sample's JSON and the view's PNG.
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

using pathlab::test::Png;
using pathlab::test::readPng;

const std::string kInspectorTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_inspector";
const std::string kInspectorBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

struct ScreenRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

// Pixels of `r` within a small distance of a colour.
int pixelsNear(const Png& png, ScreenRect r, int red, int green, int blue) {
  int n = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const int dr = png.rgb[png.index(x, y, 0)] - red, dg = png.rgb[png.index(x, y, 1)] - green,
                db = png.rgb[png.index(x, y, 2)] - blue;
      n += dr * dr + dg * dg + db * db < 30 * 30 ? 1 : 0;
    }
  return n;
}

// Camera subpath (90,200,255), light subpath (255,165,60), connections (120,240,120).
int pathPixels(const Png& png, ScreenRect r) {
  return pixelsNear(png, r, 90, 200, 255) + pixelsNear(png, r, 255, 165, 60) + pixelsNear(png, r, 120, 240, 120);
}

struct InspectorRun {
  Png png;
  std::string err;
  ScreenRect image, view3d;  // as the closing line reports them
  int generation = -1;
};

ScreenRect rectIn(const std::string& err, const std::string& label) {
  std::smatch m;
  if (!std::regex_search(err, m, std::regex(label + R"( (\d+)x(\d+)\+(\d+)\+(\d+))"))) return {};
  const int w = std::stoi(m[1]), h = std::stoi(m[2]), x = std::stoi(m[3]), y = std::stoi(m[4]);
  return {x, y, x + w, y + h};
}

InspectorRun view(const std::string& name, const std::string& script, const std::string& dir = kInspectorTmp,
                  const std::string& estimator = "") {
  const std::string out = kInspectorTmp + "/" + name + ".png";
  const pathlab::test::CommandRun r = pathlab::test::runPathlab(
      dir, "view " + kInspectorBox + " --headless --width 1280 --height 720 --render-scale 0.25 --max-length 4 --spp 2 "
                "--threads 2 --frames 20 --force " + estimator + " --script '" + script + "' --screenshot " + out,
      "cd " + dir + " &&");
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("at 2 spp"), std::string::npos) << r.err;  // the render ran on undisturbed
  InspectorRun v{readPng(out), r.err, rectIn(r.err, "image"), rectIn(r.err, "3D view")};
  std::smatch m;
  if (std::regex_search(r.err, m, std::regex(R"(\(generation (\d+)\))"))) v.generation = std::stoi(m[1]);
  EXPECT_GE(v.generation, 0) << r.err;  // the closing line names it (the comparisons of it need it)
  return v;
}

TEST(ViewerInspector, AClickDrawsTheSamplesPathsAndNextSampleChangesThem) {
  const InspectorRun none = view("none", "2:key=K;6:wait=2");
  const InspectorRun picked = view("picked", "2:key=K;6:wait=2;8:click=760,330");
  const InspectorRun next = view("next", "2:key=K;6:wait=2;8:click=760,330;13:key=N");
  ASSERT_GT(picked.png.width, 0);
  ASSERT_GT(picked.image.x1, picked.image.x0);
  EXPECT_GT(pathPixels(picked.png, picked.image), 300);
  EXPECT_LT(pathPixels(none.png, none.image), 30);
  // The next sample's paths are others.
  EXPECT_GT(picked.png.meanDifference(next.png, picked.image.x0, picked.image.y0, picked.image.x1, picked.image.y1), 0.2);
  EXPECT_EQ(next.generation, picked.generation);
}

TEST(ViewerInspector, The3DViewDrawsTheSampleFromItsOwnCameraAndOrbitingItRestartsNothing) {
  const InspectorRun plain = view("view3d-none", "2:key=K;3:key=O;6:wait=2");
  const InspectorRun picked = view("view3d-picked", "2:key=K;3:key=O;6:wait=2;8:click=560,300");
  const InspectorRun orbited = view("view3d-orbited", "2:key=K;3:key=O;6:wait=2;8:click=560,300;12:drag=1000,200>1080,240");
  ASSERT_GT(picked.view3d.x1, picked.view3d.x0) << picked.err;
  EXPECT_GE(picked.view3d.x0, picked.image.x1);  // beside the image
  // The sample's paths in the 3D view: only the render camera's marker without a pick.
  const int before = pathPixels(plain.png, plain.view3d), after = pathPixels(picked.png, picked.view3d);
  EXPECT_GT(after, before + 150) << before << " " << after;
  // The drag turned the 3D view, and only it: the render kept its generation and its image.
  const ScreenRect v = picked.view3d, i = picked.image;
  EXPECT_GT(picked.png.meanDifference(orbited.png, v.x0, v.y0, v.x1, v.y1), 2.0);
  EXPECT_EQ(orbited.generation, picked.generation);
  EXPECT_LT(picked.png.meanDifference(orbited.png, i.x0, i.y0, i.x1, i.y1), 1e-9);
}

// Warm pixels (the particles run from dim red to bright yellow).
int warmPixels(const Png& png, ScreenRect r) {
  int n = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const int red = png.rgb[png.index(x, y, 0)], green = png.rgb[png.index(x, y, 1)], blue = png.rgb[png.index(x, y, 2)];
      n += red > green && green > blue && red - blue > 70 ? 1 : 0;
    }
  return n;
}

TEST(ViewerInspector, LightParticlesAreDrawnInThe3DView) {
  const InspectorRun plain = view("particles-none", "2:key=O;6:wait=2");
  const InspectorRun particles = view("particles", "2:key=O;3:key=L;6:wait=2");
  ASSERT_GT(particles.view3d.x1, particles.view3d.x0) << particles.err;
  const int before = warmPixels(plain.png, plain.view3d), after = warmPixels(particles.png, particles.view3d);
  EXPECT_GT(after, before + 500) << before << " " << after;
  EXPECT_EQ(particles.generation, plain.generation);  // replaying them restarts nothing
}

// Strongly coloured pixels (the chains' hues at saturation 0.75; the box's walls in the 3D view
// are paler).
int vividPixels(const Png& png, ScreenRect r) {
  int n = 0;
  for (int y = r.y0; y < r.y1; ++y)
    for (int x = r.x0; x < r.x1; ++x) {
      const int red = png.rgb[png.index(x, y, 0)], green = png.rgb[png.index(x, y, 1)], blue = png.rgb[png.index(x, y, 2)];
      const int hi = std::max({red, green, blue}), lo = std::min({red, green, blue});
      n += hi > 150 && hi - lo > 110 ? 1 : 0;
    }
  return n;
}

TEST(ViewerInspector, MetropolisChainsAreDrawnInThe3DView) {
  const std::string mlt = "--integrator mlt --bootstrap 5000 --chains 200";
  const InspectorRun plain = view("chains-none", "2:key=O;6:wait=2", kInspectorTmp, mlt);
  const InspectorRun chains = view("chains", "2:key=O;3:key=L;6:wait=2", kInspectorTmp, mlt);
  ASSERT_GT(chains.view3d.x1, chains.view3d.x0) << chains.err;
  const int before = vividPixels(plain.png, plain.view3d), after = vividPixels(chains.png, chains.view3d);
  EXPECT_GT(after, before + 400) << before << " " << after;
  EXPECT_EQ(chains.generation, plain.generation);  // watching them restarts nothing
}

TEST(ViewerInspector, ExportsTheSampleAsJsonAndThe3DViewAsPng) {
  const std::string dir = kInspectorTmp + "/export";
  std::filesystem::remove_all(dir);
  const InspectorRun run = view("export", "2:key=K;3:key=O;6:wait=2;8:click=560,300;13:key=Ctrl+J;14:key=Ctrl+E", dir);
  std::string json, png;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/out")) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("pathlab-paths-") && name.ends_with(".json")) json = entry.path().string();
    if (name.starts_with("pathlab-3d-") && name.ends_with(".png")) png = entry.path().string();
  }
  ASSERT_FALSE(json.empty()) << run.err;
  ASSERT_FALSE(png.empty()) << run.err;
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["sample"], 0);
  EXPECT_EQ(j["heuristic"], "balance");
  EXPECT_FALSE(j["techniques"].empty());
  EXPECT_FALSE(j["cameraSubpath"].empty());
  const Png view3d = readPng(png);
  EXPECT_EQ(view3d.width, run.view3d.x1 - run.view3d.x0);
  EXPECT_EQ(view3d.height, run.view3d.y1 - run.view3d.y0);
  // The file is the view as the screenshot shows it.
  double difference = 0.0;
  for (int y = 0; y < view3d.height; ++y)
    for (int x = 0; x < view3d.width; ++x)
      for (int c = 0; c < 3; ++c)
        difference += std::abs(view3d.rgb[view3d.index(x, y, c)] - run.png.rgb[run.png.index(run.view3d.x0 + x, run.view3d.y0 + y, c)]);
  EXPECT_LT(difference / (3.0 * view3d.width * view3d.height), 3.0);
}

// The outlier list (issue 34): --outliers rings each of the brightest contributions on the image
// (magenta); opening the first (what a click on its row does) draws its sample's paths over the
// image and opens the 3D view beside it.
TEST(ViewerInspector, TheOutlierListMarksTheFirefliesAndOpensOne) {
  const std::string bpt = "--integrator bpt";
  const InspectorRun plain = view("outliers-none", "6:wait=2", kInspectorTmp, bpt);
  const InspectorRun marked = view("outliers", "6:wait=2", kInspectorTmp, bpt + " --outliers 5");
  const InspectorRun opened = view("outliers-open", "6:wait=2;8:outlier=1;14:wait=2", kInspectorTmp, bpt + " --outliers 5");
  const int before = pixelsNear(plain.png, plain.image, 255, 60, 220);
  const int rings = pixelsNear(marked.png, marked.image, 255, 60, 220);
  EXPECT_LT(before, 10);
  EXPECT_GT(rings, before + 60) << before << " " << rings;
  EXPECT_LT(pathPixels(marked.png, marked.image), 30);  // nothing opened
  ASSERT_GT(opened.view3d.x1, opened.view3d.x0) << opened.err;
  EXPECT_GT(pathPixels(opened.png, opened.image), 300) << opened.err;
}

}  // namespace
