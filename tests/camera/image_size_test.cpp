// The image size `pathlab render` takes from the camera's aspect ratio when --width / --height are
// not both given (core/camera/image_size.h).
#include "core/camera/image_size.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

TEST(ImageSize, NeitherSideGivenTheLongestIs512) {
  EXPECT_EQ(imageSizeForAspect(1.f, std::nullopt, std::nullopt), Vec2i(512, 512));
  EXPECT_EQ(imageSizeForAspect(1.5f, std::nullopt, std::nullopt), Vec2i(512, 341));  // 341.33 rounds down
  EXPECT_EQ(imageSizeForAspect(0.75f, std::nullopt, std::nullopt), Vec2i(384, 512));
  EXPECT_EQ(imageSizeForAspect(16.f / 9.f, std::nullopt, std::nullopt, 1280), Vec2i(1280, 720));
}

TEST(ImageSize, OneSideGivenTheOtherFollowsTheAspect) {
  EXPECT_EQ(imageSizeForAspect(1.5f, 300, std::nullopt), Vec2i(300, 200));
  EXPECT_EQ(imageSizeForAspect(1.5f, std::nullopt, 100), Vec2i(150, 100));
  EXPECT_EQ(imageSizeForAspect(1.5f, 1000, std::nullopt), Vec2i(1000, 667));  // 666.67 rounds up
  EXPECT_EQ(imageSizeForAspect(1000.f, 10, std::nullopt), Vec2i(10, 1));      // never 0
}

TEST(ImageSize, BothSidesGivenAreTakenAsTheyAre) {
  EXPECT_EQ(imageSizeForAspect(1.5f, 64, 64), Vec2i(64, 64));
  EXPECT_EQ(imageSizeForAspect(std::nullopt, 48, 36), Vec2i(48, 36));
}

TEST(ImageSize, NoAspectIsSquare) {
  EXPECT_EQ(imageSizeForAspect(std::nullopt, std::nullopt, std::nullopt), Vec2i(512, 512));
  EXPECT_EQ(imageSizeForAspect(std::nullopt, 200, std::nullopt), Vec2i(200, 200));
}

TEST(ImageSize, AnOverrideWithoutAspectKeepsTheScenes) {
  CameraDesc scene, look;
  scene.aspectRatio = 1.5f;
  EXPECT_EQ(cameraAspect(std::nullopt, scene), 1.5f);
  EXPECT_EQ(cameraAspect(look, scene), 1.5f);  // a preset's look-at camera
  look.aspectRatio = 2.f;
  EXPECT_EQ(cameraAspect(look, scene), 2.f);
  EXPECT_FALSE(cameraAspect(std::nullopt, CameraDesc{}).has_value());
}

}  // namespace
}  // namespace pathlab
