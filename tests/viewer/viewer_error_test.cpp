// The viewer's live error measurement end to end, offscreen: a reference from `pathlab render`,
// two configurations one after the other (a key switches the MIS heuristic), and the series the
// viewer exported: two of them, each falling. The error view changes the picture; a broken
// reference is one line and a non-zero exit.
#include "tests/viewer/pathlab_process.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <stb/stb_image.h>
#include <sys/wait.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

const std::string kErrorTmp = std::string(PATHLAB_TEST_TMP) + "/viewer_error";
const std::string kErrorBox = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";

using pathlab::test::CommandRun;
using pathlab::test::Png;
using pathlab::test::readPng;

CommandRun run(const std::string& args) { return pathlab::test::runPathlab(kErrorTmp, args); }

// A small reference, rendered once for every test of this process (CTest runs each test in a
// process of its own, in parallel) and removed when the process ends.
struct Reference {
  std::string path = kErrorTmp + "/reference-" + std::to_string(getpid()) + ".exr";
  Reference() {
    const CommandRun r = run("render " + kErrorBox + " -o " + path +
                             " --width 80 --height 60 --spp 400 --max-length 4 --integrator pt --seed 99 --threads 2 --force");
    EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  ~Reference() { std::filesystem::remove(path); }
};

const std::string& reference() {
  static const Reference r;
  return r.path;
}

struct Point {
  uint64_t spp;
  double seconds, relMse;
};

// series id -> its points, from the CSV the viewer writes (ErrorTracker::csv).
std::map<int, std::vector<Point>> readSeries(const std::string& path) {
  std::map<int, std::vector<Point>> out;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "series,label,generation,seconds,spp,rmse,relmse,mape");
  while (std::getline(in, line)) {
    // series,"label",generation,seconds,spp,rmse,relmse,mape (the label may hold commas)
    const size_t q0 = line.find('"'), q1 = line.find('"', q0 + 1);
    const int id = std::stoi(line.substr(0, q0 - 1));
    std::stringstream rest(line.substr(q1 + 2));
    std::string field;
    std::vector<std::string> f;
    while (std::getline(rest, field, ',')) f.push_back(field);
    if (f.size() != 6) {
      ADD_FAILURE() << "bad line: " << line;
      continue;
    }
    out[id].push_back({std::stoull(f[2]), std::stod(f[1]), std::stod(f[4])});
  }
  return out;
}

TEST(ViewerError, TwoConfigurationsTwoSeriesBothFalling) {
  const std::string csv = kErrorTmp + "/series.csv", shot = kErrorTmp + "/series.png";
  // U at frame 21 switches balance to power: a new generation, a second series. Each runs until it
  // has 8 spp (wait=8), however loaded the machine. The first frame renders a placeholder size
  // until the reference's is applied: no series for that.
  const CommandRun r = run("view " + kErrorBox + " --reference " + reference() +
                    " --headless --width 640 --height 480 --max-length 4 --threads 2 --frames 42"
                    " --script '20:wait=8;21:key=U;40:wait=8' --error-csv " + csv + " --screenshot " + shot + " --force");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.err.find("rendered 80x60"), std::string::npos) << "rendered at the reference's size: " << r.err;
  EXPECT_NE(r.err.find("2 error series"), std::string::npos) << r.err;
  const std::map<int, std::vector<Point>> series = readSeries(csv);
  ASSERT_EQ(series.size(), 2u);
  for (const auto& [id, points] : series) {
    ASSERT_GE(points.size(), 5u) << "series " << id << ": 1, 2, 3, 4, 5 spp at least";
    EXPECT_EQ(points.front().spp, 1u) << "series " << id << " starts at its first full pass";
    for (size_t i = 1; i < points.size(); ++i) {
      EXPECT_GT(points[i].spp, points[i - 1].spp);
      EXPECT_GE(points[i].seconds, points[i - 1].seconds);
    }
    // relMSE falls about as 1/N: from 1 spp to 8 or more it drops by far more than half.
    EXPECT_LT(points.back().relMse, 0.5 * points.front().relMse)
        << "series " << id << ": " << points.front().relMse << " -> " << points.back().relMse;
  }
}

// The error view shows viridis, whose colours have more blue than red below t = 0.6: the box's
// red and white walls turn blue-green-purple. Without it the left wall stays red.
TEST(ViewerError, ErrorViewShowsTheErrorInViridis) {
  const std::string plain = kErrorTmp + "/plain.png", error = kErrorTmp + "/error.png";
  const std::string common = "view " + kErrorBox + " --reference " + reference() +
                             " --headless --width 640 --height 480 --max-length 4 --threads 2 --frames 12 --spp 4"
                             " --hide-ui --force --screenshot ";
  CommandRun r = run(common + plain);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  r = run(common + error + " --error-view");
  ASSERT_EQ(r.exitCode, 0) << r.err;
  const Png a = readPng(plain), b = readPng(error);
  ASSERT_EQ(a.width, 640);
  ASSERT_EQ(b.width, 640);
  // The whole window is image (80 x 60 scaled up to 640 x 480); count red-dominated pixels.
  auto redDominated = [](const Png& p) {
    size_t n = 0;
    for (size_t i = 0; i + 2 < p.rgb.size(); i += 3) n += p.rgb[i] > p.rgb[i + 2] + 40 && p.rgb[i] > p.rgb[i + 1] + 40;
    return n;
  };
  EXPECT_GT(redDominated(a), 5000u);
  EXPECT_LT(redDominated(b), 500u);
}

void writePfm(const std::string& path, int w, int h, const std::vector<float>& rgb) {
  std::ofstream out(path, std::ios::binary);
  out << "PF\n" << w << " " << h << "\n-1.0\n";
  out.write(reinterpret_cast<const char*>(rgb.data()), static_cast<std::streamsize>(rgb.size() * sizeof(float)));
}

TEST(ViewerError, BrokenReferencesAreOneLine) {
  std::filesystem::create_directories(kErrorTmp);  // this test may be the file's first to run
  const std::string nan = kErrorTmp + "/nan.pfm";
  std::vector<float> rgb(3 * 8 * 6, 0.5f);
  rgb[7] = std::numeric_limits<float>::quiet_NaN();
  writePfm(nan, 8, 6, rgb);
  const std::string png = kErrorTmp + "/reference.png";
  std::ofstream(png) << "not really";
  const std::string shot = " --headless --frames 2 --force --screenshot " + kErrorTmp + "/x.png";
  for (const std::string& args : {"view " + kErrorBox + " --reference " + nan + shot,
                                  "view " + kErrorBox + " --reference " + png + shot,
                                  "view " + kErrorBox + " --reference /nonexistent/ref.exr" + shot,
                                  "view " + kErrorBox + " --error-csv " + kErrorTmp + "/e.csv" + shot}) {
    const CommandRun r = run(args);
    EXPECT_EQ(r.exitCode, 1) << args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
  }
}

}  // namespace
