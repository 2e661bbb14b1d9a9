// The viewer's environment controls end to end (issue 15), offscreen: a dropped .exr relights the
// scene in the expected direction (a dim map darkens a scene lit by the default light, strength
// brings it back), strength 0 leaves a scene without lights black, turning a map that is bright
// on one side changes the image (turning it a full circle does not), and a missing map is one
// error line while the previous environment, and its image, stay (a strength set with it applies).
#include "tests/viewer/pathlab_process.h"

#include "core/film/image_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <string>

namespace {

using pathlab::test::Png;
using pathlab::test::readPng;

const std::string kEnvTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_environment";
// A floor, two spheres and a box with no light of their own: the default light (uniform white,
// radiance 1) lights them until the viewer is given an environment.
const std::string kEnvScene = std::string(PATHLAB_SOURCE_DIR) + "/assets/environment.gltf";

struct EnvRun {
  Png png;
  std::string err;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the image region the closing line reports
  double meanIn(const Png& p) const {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) sum += p.rgb[p.index(x, y, c)];
    return sum / (3.0 * (x1 - x0) * (y1 - y0));
  }
  double mean() const { return meanIn(png); }
  double differenceTo(const EnvRun& o) const { return png.meanDifference(o.png, x0, y0, x1, y1); }
};

// The last frame waits for the relit scene's 4 samples per pixel (FRAME:wait and --spp wait for
// a load in progress first).
EnvRun viewWith(const std::string& name, const std::string& script, const std::string& scene = kEnvScene) {
  const std::string out = kEnvTmp + "/" + name + ".png";
  const pathlab::test::CommandRun r = pathlab::test::runPathlab(
      kEnvTmp, "view " + scene + " --headless --width 640 --height 400 --render-scale 0.5 --integrator pt "
                   "--max-length 3 --spp 4 --threads 2 --frames 10 --force" +
                   (script.empty() ? "" : " --script '" + script + "'") + " --screenshot " + out);
  EXPECT_EQ(r.exitCode, 0) << r.err;
  EnvRun v{readPng(out), r.err};
  std::smatch m;
  if (std::regex_search(r.err, m, std::regex(R"(image (\d+)x(\d+)\+(\d+)\+(\d+))"))) {
    v.x0 = std::stoi(m[3]);
    v.y0 = std::stoi(m[4]);
    v.x1 = v.x0 + std::stoi(m[1]);
    v.y1 = v.y0 + std::stoi(m[2]);
  }
  EXPECT_GT(v.x1, v.x0) << r.err;
  return v;
}

// An equirectangular map of 16 x 8 texels: `left` on the map's left half (the -x side of the
// scene), `right` on the other.
std::string writeMap(const std::string& name, float left, float right) {
  std::filesystem::create_directories(kEnvTmp);
  pathlab::Image map;
  map.width = 16;
  map.height = 8;
  for (int y = 0; y < map.height; ++y)
    for (int x = 0; x < map.width; ++x)
      for (int c = 0; c < 3; ++c) map.rgb.push_back(x < map.width / 2 ? left : right);
  const std::string path = kEnvTmp + "/" + name + ".exr";
  std::filesystem::remove(path);
  pathlab::writeImage(path, map);
  return path;
}

TEST(ViewerEnvironment, ADroppedMapRelightsTheSceneAndStrengthScalesIt) {
  const std::string dim = writeMap("dim", 0.2f, 0.2f);
  const EnvRun lit = viewWith("default-light", "");
  const EnvRun dropped = viewWith("dropped-dim", "2:drop=" + dim);
  const EnvRun stronger = viewWith("dropped-dim-x5", "2:drop=" + dim + ";4:strength=5");
  // Radiance 0.2 instead of 1: far darker (the sRGB curve makes it about half, not a fifth).
  EXPECT_LT(dropped.mean(), 0.7 * lit.mean()) << dropped.err;
  EXPECT_GT(dropped.mean(), 0.2 * lit.mean()) << dropped.err;  // but lit
  // 0.2 x 5 is the default light's radiance again: the same picture up to noise.
  EXPECT_LT(stronger.differenceTo(lit), 0.25 * dropped.differenceTo(lit)) << stronger.err;
}

// The section's "next-event lights" (script light-sampler=): many-lights.gltf opens with a light
// BVH (more than one emitter); choosing power relights it, and the closing line says which the
// shown scene uses. A value it does not know is refused before the viewer opens.
TEST(ViewerEnvironment, NextEventLightChoiceRelightsTheScene) {
  const std::string many = std::string(PATHLAB_SOURCE_DIR) + "/assets/many-lights.gltf";
  const EnvRun byBvh = viewWith("many-bvh", "", many);
  EXPECT_NE(byBvh.err.find("next-event lights bvh"), std::string::npos) << byBvh.err;
  const EnvRun byPower = viewWith("many-power", "2:light-sampler=power", many);
  EXPECT_NE(byPower.err.find("next-event lights power"), std::string::npos) << byPower.err;
  const EnvRun back = viewWith("many-back", "2:light-sampler=power;4:light-sampler=auto", many);
  EXPECT_NE(back.err.find("next-event lights bvh"), std::string::npos) << back.err;
  const pathlab::test::CommandRun bad = pathlab::test::runPathlab(
      kEnvTmp, "view " + many + " --headless --frames 2 --screenshot " + kEnvTmp + "/bad.png --script '2:light-sampler=random'");
  EXPECT_NE(bad.exitCode, 0);
  EXPECT_NE(bad.err.find("light-sampler=auto|power|bvh"), std::string::npos) << bad.err;
}

// A uniform colour lights a scene that has no light of its own, tinted by it.
TEST(ViewerEnvironment, AUniformColourLightsASceneWithoutLights) {
  const EnvRun blue = viewWith("uniform-blue", "2:environment=0.5,0.7,1");
  EXPECT_GT(blue.mean(), 20.0) << blue.err;
  double red = 0.0, bluish = 0.0;
  for (int y = blue.y0; y < blue.y1; ++y)
    for (int x = blue.x0; x < blue.x1; ++x) {
      red += blue.png.rgb[blue.png.index(x, y, 0)];
      bluish += blue.png.rgb[blue.png.index(x, y, 2)];
    }
  EXPECT_GT(bluish, 1.2 * red) << blue.err;
}

// On the Cornell box (its own lamp, an open front): strength 0 adds nothing, strength 1 the
// environment's light through the opening. (A scene with no light of its own and an environment of
// strength 0 has no light at all: it is refused, as by the command line.)
TEST(ViewerEnvironment, StrengthZeroAddsNothingAndOneAddsTheEnvironment) {
  const std::string box = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";
  const EnvRun none = viewWith("box-none", "", box);
  const EnvRun zero = viewWith("box-strength-0", "2:environment=2,2,2;4:strength=0", box);
  const EnvRun one = viewWith("box-strength-1", "2:environment=2,2,2;4:strength=0;6:wait=1;7:strength=1", box);
  EXPECT_EQ(zero.err.find("shown:"), std::string::npos) << zero.err;
  EXPECT_GT(one.mean(), none.mean() + 10.0) << one.err;
  EXPECT_LT(zero.differenceTo(none), 0.2 * one.differenceTo(none)) << zero.err;
}

TEST(ViewerEnvironment, TurningAOneSidedMapChangesTheImage) {
  const std::string oneSided = writeMap("one-sided", 3.f, 0.f);
  const EnvRun unturned = viewWith("turn-0", "2:drop=" + oneSided);
  const EnvRun half = viewWith("turn-180", "2:drop=" + oneSided + ";4:rotation=180");
  const EnvRun full = viewWith("turn-360", "2:drop=" + oneSided + ";4:rotation=360");
  EXPECT_GT(half.differenceTo(unturned), 10.0) << half.err;
  // A full turn is the same map: the same image but for the rounding of the turn.
  EXPECT_LT(full.differenceTo(unturned), 0.1 * half.differenceTo(unturned)) << full.err;
}

TEST(ViewerEnvironment, AMissingMapIsOneLineAndTheEnvironmentStays) {
  const std::string dim = writeMap("kept", 0.2f, 0.2f);
  const std::string missing = kEnvTmp + "/no-such-map.exr";
  const EnvRun before = viewWith("before-missing", "2:drop=" + dim);
  const EnvRun after = viewWith("after-missing", "2:drop=" + dim + ";4:wait=1;5:drop=" + missing);
  const std::string line = "pathlab view: shown: " + missing + ": no such file (the previous environment is kept)";
  EXPECT_NE(after.err.find(line), std::string::npos) << after.err;
  EXPECT_EQ(before.err.find("shown:"), std::string::npos) << before.err;
  // Still the dim map's image, not the default light's.
  EXPECT_LT(after.differenceTo(before), 1.0) << after.err;
  // Only the map is taken back: a strength set with it still applies, to the previous map.
  const EnvRun stronger = viewWith("after-missing-x5", "2:drop=" + dim + ";4:wait=1;5:drop=" + missing + ";5:strength=5");
  EXPECT_NE(stronger.err.find(line), std::string::npos) << stronger.err;
  EXPECT_GT(stronger.mean(), 1.3 * before.mean()) << stronger.err;
}

}  // namespace
