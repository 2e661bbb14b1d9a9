// Named presets: the shipped file parses and every preset renders; bad files give one line naming
// the file, the preset and the problem.
#include "ui/presets/presets.h"

#include "core/bpt/technique_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <memory>
#include <sys/stat.h>
#include <thread>

namespace pathlab::ui {
namespace {

const std::string kShipped = std::string(PATHLAB_SOURCE_DIR) + "/assets/presets.json";

TEST(Presets, ShippedFileParsesAndEveryPresetIsRenderable) {
  const std::vector<NamedPreset> presets = loadPresets(kShipped);
  ASSERT_GE(presets.size(), 5u);
  RenderSettings base;
  base.width = 320;
  base.height = 200;
  for (const NamedPreset& p : presets) {
    const RenderSettings s = p.applyTo(base);
    EXPECT_NO_THROW(validateSettings(s)) << p.name;
    EXPECT_EQ(s.width, 320) << p.name;  // the image size is the window's, never the preset's
  }
  EXPECT_EQ(findPreset(presets, "light tracing (t = 1)", kShipped).techniques, TechniqueSet::lightTracing());
  // The seed's comparisons: the three techniques of direct light and the four of one bounce,
  // each alone and unweighted (issue 14).
  int direct = 0, bounce = 0;
  for (const NamedPreset& p : presets) {
    if (!p.isolate || !p.isolate->unweighted || p.compare || p.isolate->technique().isMerge()) continue;
    direct += p.isolate->s + p.isolate->t - 1 == 2 ? 1 : 0;
    bounce += p.isolate->s + p.isolate->t - 1 == 3 ? 1 : 0;
  }
  EXPECT_EQ(direct, 3);
  EXPECT_EQ(bounce, 4);
  // Vertex merging has presets of its own (issue 32): VCM, and a merge isolated.
  EXPECT_TRUE(std::any_of(presets.begin(), presets.end(), [](const NamedPreset& p) {
    return !p.compare && p.techniques == TechniqueSet::parse("all;m=all");
  }));
  EXPECT_TRUE(std::any_of(presets.begin(), presets.end(),
                          [](const NamedPreset& p) { return p.isolate && p.isolate->technique().isMerge(); }));
}

// vcm, bpm and ppm as on the command line (their technique sets, ppm's merge site), and a merge
// isolated by its --isolate text; a preset's merge site replaces the current one.
TEST(Presets, MergingIntegratorsAndIsolatedMerges) {
  const auto presets = parsePresets(R"({"presets": [
      {"name": "vcm", "integrator": "vcm"},
      {"name": "bpm", "integrator": "bpm"},
      {"name": "ppm", "integrator": "ppm"},
      {"name": "merge", "integrator": "vcm", "isolate": "M2,3", "unweighted": true, "maxLength": 5},
      {"name": "connection", "isolate": "1,2"}]})",
                                    "p.json");
  ASSERT_EQ(presets.size(), 5u);
  EXPECT_EQ(presets[0].integrator, IntegratorKind::Bpt);
  EXPECT_EQ(presets[0].techniques, TechniqueSet::parse("all;m=all"));
  EXPECT_EQ(presets[0].mergeSite, MergeSite::Every);
  EXPECT_EQ(presets[1].techniques, TechniqueSet::parse("m=all"));
  EXPECT_EQ(presets[2].techniques, TechniqueSet::parse("s=0;m=all"));
  EXPECT_EQ(presets[2].mergeSite, MergeSite::FirstNonSpecular);
  EXPECT_EQ(*presets[3].isolate, (Isolation{2, 3, true, TechniqueKind::Merge}));
  EXPECT_EQ(*presets[4].isolate, (Isolation{1, 2, false}));
  RenderSettings current;
  const RenderSettings ppm = presets[2].applyTo(current);
  EXPECT_EQ(ppm.mergeSite, MergeSite::FirstNonSpecular);
  EXPECT_NO_THROW(validateSettings(presets[3].applyTo(current)));
  // Leaving ppm by a preset that does not name it merges everywhere again.
  EXPECT_EQ(presets[0].applyTo(ppm).mergeSite, MergeSite::Every);
}

// Medium sampling (the path tracer in media): set by the preset that names it, back to the
// integrator's default by one that does not (a bidirectional preset would be refused otherwise).
TEST(Presets, MediumSampling) {
  const auto presets = parsePresets(R"({"presets": [
      {"name": "distance", "integrator": "pt", "mediumSampling": "distance"},
      {"name": "bpt", "integrator": "bpt"}]})",
                                    "p.json");
  ASSERT_EQ(presets.size(), 2u);
  const RenderSettings distance = presets[0].applyTo(RenderSettings{});
  EXPECT_EQ(distance.mediumSampling, MediumSampling::Distance);
  RenderSettings equiangular;
  equiangular.integrator = IntegratorKind::Pt;
  equiangular.mediumSampling = MediumSampling::Equiangular;
  const RenderSettings bpt = presets[1].applyTo(equiangular);
  EXPECT_FALSE(bpt.mediumSampling);
  EXPECT_NO_THROW(validateSettings(bpt));
}

// Metropolis (issue 33): "integrator": "mlt" sets it, with its compare lane; an isolation with it
// is refused at parse time.
TEST(Presets, Metropolis) {
  const auto presets = parsePresets(R"({"presets": [
      {"name": "mlt", "integrator": "mlt", "compare": "bpt"}]})",
                                    "p.json");
  ASSERT_EQ(presets.size(), 1u);
  const RenderSettings s = presets[0].applyTo(RenderSettings{});
  EXPECT_EQ(s.integrator, IntegratorKind::Mlt);
  EXPECT_NO_THROW(validateSettings(s));
  EXPECT_THROW(parsePresets(R"({"presets": [{"name": "x", "integrator": "mlt", "isolate": [1, 2]}]})", "p.json"),
               PresetError);
}

TEST(Presets, FieldsAndDefaults) {
  const auto presets = parsePresets(R"({"presets": [
      {"name": "a"},
      {"name": "b", "integrator": "lt", "techniques": "t=1", "mis": "power", "beta": 3, "minConnection": 0.05,
       "maxLength": 4, "isolate": [2, 1], "unweighted": true,
       "camera": {"eye": [0, 1, 2], "target": [0, 1, 0], "yfovDegrees": 60}}]})",
                                    "p.json");
  ASSERT_EQ(presets.size(), 2u);
  EXPECT_EQ(presets[0].integrator, IntegratorKind::Bpt);
  EXPECT_EQ(presets[0].techniques, TechniqueSet::all());
  EXPECT_EQ(presets[0].maxLength, 10);
  EXPECT_EQ(presets[0].mis.minConnection, kDefaultMinConnection);
  EXPECT_FALSE(presets[0].isolate);
  EXPECT_FALSE(presets[0].camera);
  const NamedPreset& b = presets[1];
  EXPECT_EQ(b.integrator, IntegratorKind::Lt);
  EXPECT_EQ(b.mis.heuristic, MisHeuristic::Power);
  EXPECT_EQ(b.mis.beta, 3.f);
  EXPECT_EQ(b.mis.minConnection, 0.05f);
  EXPECT_EQ(*b.isolate, (Isolation{2, 1, true}));
  ASSERT_TRUE(b.camera);
  EXPECT_NEAR(b.camera->yfov, glm::radians(60.f), 1e-6f);
  EXPECT_NEAR(b.camera->cameraToWorld[3].z, 2.f, 1e-6f);
  EXPECT_NEAR(b.camera->cameraToWorld[2].z, 1.f, 1e-6f);  // looks down -z: camera z axis is +z

  // A preset without a camera keeps the current one.
  RenderSettings current;
  current.camera = b.camera;
  EXPECT_EQ(presets[0].applyTo(current).camera, b.camera);
}

struct BadCase {
  const char* json;
  const char* expected;  // part of the message
};

// Short test names in CTest: the expected part of the message.
void PrintTo(const BadCase& c, std::ostream* os) { *os << c.expected; }

class BadPresets : public testing::TestWithParam<BadCase> {};

TEST_P(BadPresets, OneLineNamingFileAndProblem) {
  try {
    parsePresets(GetParam().json, "dir/talk.json");
    FAIL() << "no error for " << GetParam().json;
  } catch (const PresetError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("dir/talk.json: ", 0), 0u) << what;
    EXPECT_NE(what.find(GetParam().expected), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Presets, BadPresets,
    testing::Values(BadCase{"{\"presets\": [", "parse error"}, BadCase{"[]", "\"presets\""},
                    BadCase{R"({"presets": [{"techniques": "all"}]})", "no \"name\""},
                    BadCase{R"({"presets": [{"name": "x", "colour": 1}]})", "unknown key \"colour\""},
                    BadCase{R"({"presets": [{"name": "x", "techniques": "9;x"}]})", "preset 0 (\"x\"): techniques"},
                    BadCase{R"({"presets": [{"name": "x", "techniques": "4,4", "maxLength": 6}]})",
                            "(4,4) has length 7"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "sppm"}]})", "sppm"},
                    BadCase{R"({"presets": [{"name": "x", "mis": "max"}]})", "max"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "pt", "mediumSampling": "far"}]})",
                            "mediumSampling \"far\" is not distance, equiangular or mis"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "lt", "mediumSampling": "mis"}]})",
                            "the lt integrator samples distances"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "vcm", "mediumSampling": "mis"}]})",
                            "merging techniques' weights do not count"},
                    BadCase{R"({"presets": [{"name": "x", "maxLength": 0}]})", "maxLength"},
                    BadCase{R"({"presets": [{"name": "x", "minConnection": -1}]})", "minConnection"},
                    BadCase{R"({"presets": [{"name": "x", "maxLength": "5"}]})", "an integer"},
                    BadCase{R"({"presets": [{"name": "x", "maxLength": 3, "isolate": [3, 3]}]})", "(3,3)"},
                    BadCase{R"({"presets": [{"name": "x", "isolate": [1]}]})", "[s, t]"},
                    BadCase{R"({"presets": [{"name": "x", "isolate": "M1,2"}]})", "M(1,2) is not a technique"},
                    BadCase{R"({"presets": [{"name": "x", "isolate": "M2"}]})", "'M2' is not S,T, MS,T or E1,T"},
                    BadCase{R"({"presets": [{"name": "x", "isolate": "Mx,2"}]})", "'x' is not an integer"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "vcm", "techniques": "all"}]})",
                            "integrator \"vcm\" sets the techniques"},
                    BadCase{R"({"presets": [{"name": "x", "unweighted": true}]})", "needs \"isolate\""},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "pt", "isolate": [1, 2]}]})", "bpt or lt"},
                    BadCase{R"({"presets": [{"name": "x", "integrator": "lt", "isolate": "M2,2"}]})",
                            "M(2,2): light tracing has only the t = 1 techniques"},
                    BadCase{R"({"presets": [{"name": "x", "camera": {"eye": [0, 0, 0], "target": [0, 0, 0]}}]})",
                            "coincide"},
                    BadCase{R"({"presets": [{"name": "x", "camera": {"eye": [0, 0], "target": [0, 0, 1]}}]})",
                            "3 numbers"},
                    BadCase{R"({"presets": [{"name": "x"}, {"name": "x"}]})", "preset 1 (\"x\"): duplicate"},
                    // Issue 37: no wrap-around to int (4294967300 is 4 as an int), no float overflow.
                    BadCase{R"({"presets": [{"name": "x", "maxLength": 4294967300}]})",
                            "preset 0 (\"x\"): \"maxLength\" must be in [1, 1000], not 4294967300"},
                    BadCase{R"({"presets": [{"name": "x", "maxLength": -4294967295}]})", "not -4294967295"},
                    BadCase{R"({"presets": [{"name": "x", "isolate": [4294967297, 1]}]})", "not 4294967297"},
                    BadCase{R"({"presets": [{"name": "x", "camera": {"eye": [1e39, 0, 0], "target": [0, 0, 1]}}]})",
                            "preset 0 (\"x\"): camera eye 1e+39 is not a finite 32-bit number"},
                    BadCase{R"({"presets": [{"name": "x", "beta": 1e300}]})", "\"beta\" 1e+300 is not a finite"},
                    // A JSON string may hold a newline: escaped, the message stays one line (found by presets_fuzz).
                    BadCase{"{\"presets\": [{\"name\": \"x\", \"maxL\\ngth\": 5}]}", "unknown key \"maxL\\ngth\""},
                    BadCase{"{\"presets\": [{\"name\": \"a\\nb\", \"mis\": \"?\"}]}", "preset 0 (\"a\\nb\")"},
                    // A number that overflows a double is nlohmann's out_of_range, not a parse_error.
                    BadCase{R"({"presets": [{"name": "x", "beta": 1e999}]})", "1e999"}),
    [](const testing::TestParamInfo<BadCase>& info) { return "case" + std::to_string(info.index); });

TEST(Presets, UnknownNameListsTheKnownOnes) {
  const auto presets = parsePresets(R"({"presets": [{"name": "a"}, {"name": "b"}]})", "p.json");
  try {
    findPreset(presets, "c", "p.json");
    FAIL();
  } catch (const PresetError& e) {
    EXPECT_STREQ(e.what(), "p.json: no preset \"c\" (known: \"a\", \"b\")");
  }
}

TEST(Presets, MissingFile) {
  EXPECT_THROW(loadPresets("/nonexistent/presets.json"), PresetError);
}

// Read through the guarded reader: a FIFO is refused at once (the read would wait for a writer).
TEST(Presets, FifoIsRefusedWithoutBlocking) {
  const std::string fifo = std::string(PATHLAB_TEST_TMP) + "/presets-fifo.json";
  std::filesystem::create_directories(PATHLAB_TEST_TMP);
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  auto done = std::make_shared<std::promise<std::string>>();
  std::future<std::string> message = done->get_future();
  std::thread([done, fifo] {
    try {
      loadPresets(fifo);
      done->set_value("");
    } catch (const PresetError& e) {
      done->set_value(e.what());
    }
  }).detach();
  ASSERT_EQ(message.wait_for(std::chrono::seconds(10)), std::future_status::ready) << "blocked on a FIFO";
  EXPECT_EQ(message.get(), fifo + ": cannot read the presets file: is a FIFO, not a regular file");
}

}  // namespace
}  // namespace pathlab::ui
