// The environment a loaded scene gets (LoadOptions): the one asked for, whether or not the file
// has lights; the default light (a uniform white environment of radiance 1, one notice) for a file
// with no light of its own; and today's refusal without it.
#include "core/scene/gltf_loader.h"
#include "core/scene/scene.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace pathlab {
namespace {

const std::string kSource = PATHLAB_SOURCE_DIR;
const std::string kNoLight = kSource + "/tests/scenes/bad/no-emitter.gltf";

int notices(const SceneDesc& d) {
  return static_cast<int>(std::count_if(d.warnings.begin(), d.warnings.end(), [](const std::string& w) {
    return w.find("uniform white environment of radiance 1") != std::string::npos;
  }));
}

TEST(GltfEnvironment, DefaultLightForAFileWithoutLights) {
  LoadOptions options;
  options.defaultLight = true;
  const SceneDesc d = loadGltf(kNoLight, options);
  ASSERT_TRUE(d.environment);
  EXPECT_TRUE(d.environment->isConstant());
  EXPECT_EQ(d.environment->constant, Spectrum(1.f));
  EXPECT_EQ(d.environment->strength, 1.f);
  EXPECT_EQ(notices(d), 1);
  const Scene scene{SceneDesc(d)};
  ASSERT_EQ(scene.lights().size(), 1u);
  EXPECT_EQ(scene.lights().environment(), 0);
  EXPECT_EQ(scene.lights()[0].type(), LightType::Environment);
}

TEST(GltfEnvironment, WithoutTheDefaultLightAFileWithoutLightsIsRefused) {
  try {
    loadGltf(kNoLight);
    FAIL() << "loaded";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("no light source"), std::string::npos) << e.what();
  }
}

// A file whose only emission is an emissive texture (textured.gltf without its point light, as
// DamagedHelmet) glows but is not lit by it: the default light joins its glowing triangles, with a
// notice saying so. With the point light, or an untextured emitter, it lights itself.
TEST(GltfEnvironment, GlowingTexturesAloneGetTheDefaultLightToo) {
  nlohmann::json file = nlohmann::json::parse(std::ifstream(kSource + "/tests/scenes/textured.gltf"));
  for (nlohmann::json& node : file["nodes"]) node.erase("extensions");
  const std::filesystem::path dir = std::filesystem::path(PATHLAB_TEST_TMP) / "gltf_environment";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "glow-only.gltf") << file.dump();
  LoadOptions options;
  options.defaultLight = true;
  const SceneDesc glowing = loadGltf((dir / "glow-only.gltf").string(), options);
  ASSERT_TRUE(glowing.environment);
  EXPECT_EQ(glowing.environment->constant, Spectrum(1.f));
  EXPECT_EQ(notices(glowing), 1);
  EXPECT_TRUE(std::any_of(glowing.warnings.begin(), glowing.warnings.end(),
                          [](const std::string& w) { return w.find("emissive textures") != std::string::npos; }));
  const Scene scene{SceneDesc(glowing)};
  EXPECT_GT(scene.lights().size(), 1u);  // the glowing triangles stay lights beside it
  EXPECT_FALSE(loadGltf(kSource + "/tests/scenes/textured.gltf", options).environment);
  options.defaultLight = false;
  EXPECT_FALSE(loadGltf((dir / "glow-only.gltf").string(), options).environment);
}

TEST(GltfEnvironment, TheFilesOwnLightsNeedNoDefault) {
  LoadOptions options;
  options.defaultLight = true;
  const SceneDesc d = loadGltf(kSource + "/assets/cornell-box.gltf", options);
  EXPECT_FALSE(d.environment);
  EXPECT_EQ(notices(d), 0);
}

// An environment asked for lights the scene beside its own lights, with no notice, and is chosen
// among them by power.
TEST(GltfEnvironment, AnEnvironmentJoinsTheFilesLights) {
  LoadOptions options;
  auto env = std::make_shared<EnvironmentDesc>();
  env->constant = Spectrum(0.5f);
  options.environment = env;
  options.defaultLight = true;
  const Scene scene(loadGltf(kSource + "/assets/cornell-box.gltf", options));
  const int e = scene.lights().environment();
  ASSERT_GE(e, 0);
  EXPECT_GT(scene.lights().size(), 1u);
  double total = 0.0;
  for (size_t i = 0; i < scene.lights().size(); ++i) total += luminance(scene.lights()[i].power());
  EXPECT_NEAR(scene.lights().pmf(e), luminance(scene.lights()[static_cast<size_t>(e)].power()) / total, 1e-5);
  EXPECT_EQ(notices(loadGltf(kNoLight, options)), 0);  // the environment asked for is no default
}

// Issue 37: each factor fits a float, their product over the sphere does not; refused in one line
// naming the map and the option instead of rendering with every environment sample dropped as Inf.
TEST(GltfEnvironment, AnEnvironmentWhosePowerOverflowsIsRefused) {
  LoadOptions options;
  auto env = std::make_shared<EnvironmentDesc>();
  env->source = "bright.exr";
  env->width = 2;
  env->height = 1;
  env->texels = {Spectrum(1e35f), Spectrum(1.f)};
  env->strength = 1e6f;
  options.environment = env;
  try {
    const Scene scene(loadGltf(kSource + "/assets/cornell-box.gltf", options));
    FAIL() << "the overflowing environment was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("bright.exr: radiance up to 1e+35 x --environment-strength 1e+06 overflows", 0), 0u) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  env->strength = 1.f;  // 1e35 alone fits
  EXPECT_NO_THROW(Scene(loadGltf(kSource + "/assets/cornell-box.gltf", options)));
}

}  // namespace
}  // namespace pathlab
