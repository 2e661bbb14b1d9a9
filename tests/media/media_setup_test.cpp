// Media set-up scales with the objects (issue 37): many small objects inside a fog box get the fog
// as their outside medium in time linear in their number, where the per-object containment test
// used to walk every mesh of the scene (40,000 objects: 40 s).
#include "core/scene/scene_media.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <chrono>

namespace pathlab {
namespace {

TEST(MediaSetup, ManySmallObjectsInFogAreSetUpInLinearTime) {
  SceneDesc desc = test::foggyFurnace(0.5f, 1.f, 0.5f, 0.f);
  const size_t fogMeshes = desc.meshes.size();
  constexpr int kSide = 40;  // 64,000 small quads on a grid inside the fog box (-0.999 .. 0.999)
  for (int x = 0; x < kSide; ++x)
    for (int y = 0; y < kSide; ++y)
      for (int z = 0; z < kSide; ++z) {
        const Vec3 c = Vec3(-0.9f) + 1.8f * Vec3(float(x), float(y), float(z)) / float(kSide - 1);
        const float s = 0.005f;
        desc.meshes.push_back(test::quad(c + Vec3(-s, 0, s), c + Vec3(s, 0, s), c + Vec3(s, 0, -s), c + Vec3(-s, 0, -s), 0));
      }
  const auto start = std::chrono::steady_clock::now();
  const SceneMedia media(desc);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 5.0) << "quadratic media set-up";
  for (size_t m = fogMeshes; m < desc.meshes.size(); m += 997) {
    EXPECT_EQ(media.mesh(m).outside, 0) << m;
    EXPECT_EQ(media.mesh(m).inside, 0) << m;
  }
  EXPECT_EQ(media.mediumAt(Vec3(0.95f, -0.95f, 0.95f)), 0);
  EXPECT_EQ(media.mediumAt(Vec3(1.5f)), -1);
}

}  // namespace
}  // namespace pathlab
