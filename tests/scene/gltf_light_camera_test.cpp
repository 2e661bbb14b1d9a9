// Tests of the glTF loader's punctual lights (KHR_lights_punctual) and its camera.
#include "core/scene/gltf_loader.h"
#include "tests/scene/gltf_test_builder.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

using namespace gltf_test;

TEST(GltfLights, PunctualLightsTakePositionAndMinusZFromTheirNode) {
  TestGltf g;
  g.light = false;
  g.extensions = R"("KHR_lights_punctual":{"lights":[
    {"type":"point","color":[1,0.5,0.25],"intensity":10,"range":3},
    {"name":"cone","type":"spot","intensity":2,"spot":{"outerConeAngle":0.5}},
    {"type":"directional","intensity":3},
    {"type":"spot","spot":{}}]})";
  auto lightNode = [](int light, const std::string& members) {
    return R"({"extensions":{"KHR_lights_punctual":{"light":)" + str(light) + "}}" +
           (members.empty() ? "" : "," + members) + "}";
  };
  g.root(lightNode(0, R"("translation":[1,2,3])"));
  const int spot = g.node(lightNode(1, R"("translation":[0,1,0])"));
  // Parent: translate and scale by 2; the spot's direction stays unit, its position scales.
  g.root(R"({"translation":[5,0,0],"scale":[2,2,2],"children":[)" + str(spot) + "]}");
  // 90 degrees about +x: -z -> +y.
  g.root(lightNode(2, R"("rotation":[0.70710678,0,0,0.70710678])"));
  g.root(lightNode(3, ""));
  const SceneDesc d = loadGltf(g.write("lights.gltf"));
  EXPECT_TRUE(d.meshes.empty());
  ASSERT_EQ(d.punctualLights.size(), 4u);
  const PunctualLightDesc& point = d.punctualLights[0];
  EXPECT_EQ(point.type, PunctualLightType::Point);
  expectNear(point.position, {1, 2, 3});
  expectNear(point.color, {1, 0.5f, 0.25f});
  EXPECT_FLOAT_EQ(point.intensity, 10.f);
  const PunctualLightDesc& cone = d.punctualLights[1];
  EXPECT_EQ(cone.type, PunctualLightType::Spot);
  EXPECT_EQ(cone.name, "cone");
  expectNear(cone.position, {5, 2, 0});
  expectNear(cone.direction, {0, 0, -1});
  EXPECT_FLOAT_EQ(cone.innerConeAngle, 0.f);
  EXPECT_FLOAT_EQ(cone.outerConeAngle, 0.5f);
  const PunctualLightDesc& sun = d.punctualLights[2];
  EXPECT_EQ(sun.type, PunctualLightType::Directional);
  expectNear(sun.direction, {0, 1, 0});
  EXPECT_FLOAT_EQ(sun.intensity, 3.f);
  // A spot light with an empty "spot" object gets the spec defaults 0 and pi/4.
  EXPECT_FLOAT_EQ(d.punctualLights[3].innerConeAngle, 0.f);
  EXPECT_NEAR(d.punctualLights[3].outerConeAngle, kPi / 4.f, 1e-6f);
  EXPECT_TRUE(d.warnings.empty()) << ::testing::PrintToString(d.warnings);  // range: no warning
}

TEST(GltfCamera, TheFirstCameraWithScaleRemoved) {
  TestGltf g;
  g.add("cameras",
        R"({"name":"unused","type":"perspective","perspective":{"yfov":0.5,"znear":0.1}})");
  g.add(
      "cameras",
      R"({"name":"main","type":"perspective","perspective":{"yfov":0.8,"aspectRatio":1.5,"znear":0.1}})");
  g.add("cameras",
        R"({"name":"later","type":"perspective","perspective":{"yfov":0.3,"znear":0.1}})");
  const int later = g.node(R"({"camera":2})");
  // 90 degrees about +y (x -> -z, z -> x), non-uniform scale, translation.
  g.root(R"({"camera":1,"translation":[1,2,3],"rotation":[0,0.70710678,0,0.70710678],
            "scale":[2,3,4],"children":[)" +
         str(later) + "]}");
  const SceneDesc d = loadGltf(g.write("camera.gltf"));
  ASSERT_TRUE(d.camera.has_value());
  const CameraDesc& c = *d.camera;
  EXPECT_EQ(c.name, "main");
  EXPECT_FLOAT_EQ(c.yfov, 0.8f);
  ASSERT_TRUE(c.aspectRatio.has_value());
  EXPECT_FLOAT_EQ(*c.aspectRatio, 1.5f);
  expectNear(Vec3(c.cameraToWorld[0]), {0, 0, -1});
  expectNear(Vec3(c.cameraToWorld[1]), {0, 1, 0});
  expectNear(Vec3(c.cameraToWorld[2]), {1, 0, 0});
  expectNear(Vec3(c.cameraToWorld[3]), {1, 2, 3});
  EXPECT_FLOAT_EQ(c.cameraToWorld[3][3], 1.f);
  EXPECT_FALSE(c.orthographic.has_value());
}

// glTF 2.0 sec. 5.13: xmag and ymag are half the view's extent; the aspect ratio follows them.
TEST(GltfCamera, OrthographicCameraWithItsMagnification) {
  TestGltf g;
  g.add("cameras", R"({"name":"plan","type":"orthographic","orthographic":{"xmag":3,"ymag":1.5,"znear":0.1,"zfar":10}})");
  g.add("cameras", R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}})");
  g.root(R"({"camera":0,"translation":[0,4,0],"rotation":[-0.70710678,0,0,0.70710678]})");
  g.root(R"({"camera":1})");
  const SceneDesc d = loadGltf(g.write("ortho.gltf"));
  ASSERT_TRUE(d.camera.has_value());
  ASSERT_TRUE(d.camera->orthographic.has_value());
  EXPECT_EQ(d.camera->name, "plan");
  EXPECT_FLOAT_EQ(d.camera->orthographic->x, 3.f);
  EXPECT_FLOAT_EQ(d.camera->orthographic->y, 1.5f);
  ASSERT_TRUE(d.camera->aspectRatio.has_value());
  EXPECT_FLOAT_EQ(*d.camera->aspectRatio, 2.f);
  expectNear(-Vec3(d.camera->cameraToWorld[2]), {0, -1, 0});  // looking down
  EXPECT_FALSE(hasWarning(d, "orthographic")) << ::testing::PrintToString(d.warnings);

  TestGltf bad;
  bad.add("cameras", R"({"type":"orthographic","orthographic":{"xmag":1,"ymag":0,"znear":0.1,"zfar":10}})");
  bad.root(R"({"camera":0})");
  try {
    loadGltf(bad.write("ortho-bad.gltf"));
    ADD_FAILURE() << "ymag 0 loaded";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("ymag"), std::string::npos) << e.what();
  }
}

TEST(GltfCamera, NoCameraAndNoAspectRatioAreFine) {
  const SceneDesc none = loadGltf(oneTriangle("nocamera.gltf", ""));
  EXPECT_FALSE(none.camera.has_value());
  TestGltf g;
  g.add("cameras", R"({"type":"perspective","perspective":{"yfov":1.0,"znear":0.1}})");
  g.root(R"({"camera":0})");
  const SceneDesc d = loadGltf(g.write("noaspect.gltf"));
  ASSERT_TRUE(d.camera.has_value());
  EXPECT_FALSE(d.camera->aspectRatio.has_value());
}

}  // namespace
}  // namespace pathlab
