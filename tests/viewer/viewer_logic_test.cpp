// Small parts of the viewer without OpenGL: the shortcut table, fresh output names, background
// scene loading with one-line errors.
#include "ui/input/input_script.h"
#include "ui/input/shortcuts.h"
#include "ui/record/output_names.h"
#include "ui/scene/scene_loader.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <algorithm>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <thread>

namespace pathlab::ui {
namespace {

TEST(Shortcuts, UniqueAndClearOfTheFlyKeys) {
  std::set<std::pair<int, bool>> keys;
  std::set<Action> actions;
  for (const Shortcut& s : shortcuts()) {
    EXPECT_TRUE(keys.insert({s.key, s.ctrl}).second) << s.keyName << " bound twice";
    EXPECT_TRUE(actions.insert(s.action).second) << s.description;
    EXPECT_GT(std::string(s.description).size(), 3u);
    if (!s.ctrl) {
      for (int fly : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
        EXPECT_NE(s.key, fly) << s.keyName << " is a fly key";
    }
  }
  EXPECT_EQ(actions.size(), static_cast<size_t>(Action::ExportView3D) + 1);  // every action has a key
}

TEST(OutputNames, NeverAnExistingFile) {
  const std::string dir = std::string(PATHLAB_TEST_TMP) + "/output_names";
  std::filesystem::remove_all(dir);
  const std::string first = freshStem(dir, "pathlab", {".exr", ".png"});
  EXPECT_EQ(first.rfind(dir + "/pathlab-", 0), 0u);
  std::ofstream(first + ".png") << "x";
  const std::string second = freshStem(dir, "pathlab", {".exr", ".png"});
  EXPECT_NE(second, first);
  EXPECT_FALSE(std::filesystem::exists(second + ".png"));
  EXPECT_FALSE(std::filesystem::exists(second + ".exr"));
}

std::optional<SceneLoadResult> waitFor(SceneLoader& loader) {
  for (int i = 0; i < 600; ++i) {
    if (auto r = loader.poll()) return r;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return std::nullopt;
}

TEST(SceneLoader, LoadsInTheBackground) {
  SceneLoader loader;
  EXPECT_FALSE(loader.busy());
  loader.start(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf");
  EXPECT_TRUE(loader.busy());
  const auto r = waitFor(loader);
  ASSERT_TRUE(r);
  ASSERT_TRUE(r->scene) << r->error;
  EXPECT_TRUE(r->error.empty());
  EXPECT_FALSE(loader.busy());
}

TEST(SceneLoader, ABrokenSceneIsOneLineNamingTheFile) {
  for (const auto& entry : std::filesystem::directory_iterator(std::string(PATHLAB_SOURCE_DIR) + "/tests/scenes/bad")) {
    const std::string ext = entry.path().extension().string();
    if ((ext != ".gltf" && ext != ".glb") || entry.path().filename() == "degenerate.gltf") continue;  // loads, warns
    SceneLoader loader;
    loader.start(entry.path().string());
    const auto r = waitFor(loader);
    ASSERT_TRUE(r);
    EXPECT_FALSE(r->scene) << entry.path();
    EXPECT_NE(r->error.find(entry.path().filename().string()), std::string::npos) << r->error;
    EXPECT_EQ(r->error.find('\n'), std::string::npos) << r->error;
  }
  const SceneLoadResult missing = SceneLoader::load("/nonexistent/box.gltf");
  EXPECT_FALSE(missing.scene);
  EXPECT_NE(missing.error.find("/nonexistent/box.gltf"), std::string::npos);
}

// Relighting (the Environment section): the scene loads with the chosen environment; a map read
// before is not read again when only strength or rotation change; a missing map is one line naming
// it, and no scene.
TEST(SceneLoader, LoadsWithTheChosenEnvironmentReadingAMapOnce) {
  const std::string box = std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf";
  SceneLoader loader;
  loader.start(box, EnvironmentChoice{"0.5,0.5,0.5", 2.f, 0.f}, nullptr);
  auto r = waitFor(loader);
  ASSERT_TRUE(r && r->scene) << (r ? r->error : "");
  ASSERT_TRUE(r->environmentDesc);
  EXPECT_EQ(r->environmentDesc->strength, 2.f);
  EXPECT_EQ(r->environment, (EnvironmentChoice{"0.5,0.5,0.5", 2.f, 0.f}));
  // A map that exists only as already read: turning it must not look for the file.
  auto read = std::make_shared<EnvironmentDesc>();
  read->source = "/nonexistent/read-before.exr";
  read->width = 2;
  read->height = 1;
  read->texels = {Spectrum(1.f), Spectrum(0.f)};
  loader.start(box, EnvironmentChoice{read->source, 1.f, 90.f}, read);
  r = waitFor(loader);
  ASSERT_TRUE(r && r->scene) << (r ? r->error : "");
  EXPECT_EQ(r->environmentDesc->rotationDegrees, 90.f);
  EXPECT_EQ(r->environmentDesc->texels.size(), 2u);
  loader.start(box, EnvironmentChoice{"/nonexistent/sky.exr", 1.f, 0.f}, read);
  r = waitFor(loader);
  ASSERT_TRUE(r);
  EXPECT_FALSE(r->scene);
  EXPECT_EQ(r->error, "/nonexistent/sky.exr: no such file");
}

}  // namespace
}  // namespace pathlab::ui

namespace pathlab::ui {
namespace {

// Issue 14: a key listed on consecutive frames (or twice on one) is pressed that many times:
// each later press waits for a frame with the key up, since ImGui counts a press as the key
// going down.
TEST(InputScript, EveryListedKeyPressCounts) {
  const std::vector<InputEvent> script = parseInputScript("5:key=];6:key=];6:key=];6:key=[");
  auto downAt = [&](int frame, int key) {
    const std::vector<int> keys = inputAt(script, frame).keysDown;
    return std::count(keys.begin(), keys.end(), key);
  };
  int presses = 0;
  bool wasDown = false;
  for (int frame = 0; frame < 20; ++frame) {
    const bool down = downAt(frame, GLFW_KEY_RIGHT_BRACKET) > 0;
    presses += down && !wasDown ? 1 : 0;
    wasDown = down;
  }
  EXPECT_EQ(presses, 3);
  EXPECT_EQ(downAt(5, GLFW_KEY_RIGHT_BRACKET), 1);
  EXPECT_EQ(downAt(7, GLFW_KEY_RIGHT_BRACKET), 1);
  EXPECT_EQ(downAt(9, GLFW_KEY_RIGHT_BRACKET), 1);
  EXPECT_EQ(downAt(6, GLFW_KEY_LEFT_BRACKET), 1);  // another key keeps its frame
}

TEST(InputScript, ParsesKeysAndDragsAndReplaysThemFrameByFrame) {
  const std::vector<InputEvent> script = parseInputScript("2:key=3;5:drag=10,20>30,40;9:key=Ctrl+S;12:key=W");
  ASSERT_EQ(script.size(), 4u);
  EXPECT_EQ(script[0].key, GLFW_KEY_3);
  EXPECT_TRUE(script[2].ctrl);
  EXPECT_EQ(inputAt(script, 1).keysDown.size(), 0u);
  EXPECT_EQ(inputAt(script, 2).keysDown, std::vector<int>{GLFW_KEY_3});
  EXPECT_EQ(inputAt(script, 3).keysDown.size(), 0u);  // pressed for one frame
  // Drag: move, press, move while pressed, release.
  const FrameInput f5 = inputAt(script, 5), f6 = inputAt(script, 6), f7 = inputAt(script, 7), f8 = inputAt(script, 8);
  EXPECT_TRUE(f5.hasMouse && !f5.mouseDown && f5.mouse == Vec2(10, 20));
  EXPECT_TRUE(f6.mouseDown && f6.mouse == Vec2(10, 20));
  EXPECT_TRUE(f7.mouseDown && f7.mouse == Vec2(30, 40));
  EXPECT_TRUE(!f8.mouseDown && f8.mouse == Vec2(30, 40));
  EXPECT_FALSE(inputAt(script, 9).hasMouse);
  EXPECT_TRUE(inputAt(script, 9).ctrl);
  EXPECT_EQ(inputAt(script, 21).keysDown, std::vector<int>{GLFW_KEY_W});  // fly keys are held
  const std::vector<InputEvent> drop = parseInputScript("3:drop=a b/c.gltf");
  EXPECT_EQ(inputAt(drop, 3).dropped, std::vector<std::string>{"a b/c.gltf"});
  EXPECT_TRUE(inputAt(drop, 4).dropped.empty());
  EXPECT_EQ(inputAt(parseInputScript("1:resize=640,480"), 1).resize, Vec2i(640, 480));
  for (const char* bad : {"1:resize=0,4", "1:resize=4", "1:drop=", "x:key=3", "1:key=nope", "1:drag=1,2", "1:press=3", "-1:key=3",
                          "1:drag=nan,2>3,4", "1:drag=1,inf>3,4", "1:drag=1,2>1e999,4", "1:environment=",
                          "1:strength=-1", "1:strength=x", "1:rotation=nan", "1:rotation=5deg"})
    EXPECT_THROW(parseInputScript(bad), std::invalid_argument) << bad;
}

// The Environment section's edits as a script sets them: one frame each, the fields it names.
TEST(InputScript, EnvironmentEditsArriveOnTheirFrame) {
  const std::vector<InputEvent> script = parseInputScript("2:environment=0.5,1,2;2:strength=4;5:rotation=-90;7:environment=none");
  const EnvironmentEdit at2 = inputAt(script, 2).environment;
  EXPECT_EQ(at2.spec, std::optional<std::string>("0.5,1,2"));
  EXPECT_EQ(at2.strength, std::optional<float>(4.f));
  EXPECT_FALSE(at2.rotationDegrees);
  EXPECT_TRUE(inputAt(script, 3).environment.empty());
  EXPECT_EQ(inputAt(script, 5).environment.rotationDegrees, std::optional<float>(-90.f));
  EnvironmentChoice choice{"sky.hdr", 2.f, 30.f};
  apply(inputAt(script, 7).environment, choice);
  EXPECT_EQ(choice, (EnvironmentChoice{"", 2.f, 30.f}));  // none keeps strength and rotation
  EXPECT_TRUE(isEnvironmentFile("maps/Sky.EXR"));
  EXPECT_FALSE(isEnvironmentFile("scene.gltf"));
}

}  // namespace
}  // namespace pathlab::ui
