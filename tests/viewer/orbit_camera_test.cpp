// The camera controller: it starts exactly at the scene's camera, orbits about its pivot at a
// constant distance, pans eye and pivot together, zooms without passing the pivot, never flips.
#include "ui/presets/presets.h"
#include "ui/scene/orbit_camera.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

constexpr float kEps = 1e-4f;

void expectNear(const Vec3& a, const Vec3& b, float eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

void expectSameCamera(const CameraDesc& a, const CameraDesc& b) {
  for (int c = 0; c < 4; ++c) expectNear(Vec3(a.cameraToWorld[c]), Vec3(b.cameraToWorld[c]));
  EXPECT_NEAR(a.yfov, b.yfov, kEps);
}

// The Cornell box's camera: at (0.278, 0.273, -0.8) looking along +z.
const CameraDesc kBoxCamera = lookAtCamera({0.278f, 0.273f, -0.8f}, {0.278f, 0.273f, 0.f}, 0.686f);
const Vec3 kBoxMin(0.f), kBoxMax(0.556f, 0.549f, 0.56f);

TEST(OrbitCamera, StartsAtTheSceneCamera) {
  const OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  expectSameCamera(orbit.desc(), kBoxCamera);
  // The pivot is on the view axis, level with the box's centre.
  expectNear(orbit.pivot(), {0.278f, 0.273f, 0.28f}, 1e-3f);
  EXPECT_NEAR(orbit.distance(), 1.08f, 1e-3f);
}

// The override camera keeps the scene camera's aspect, so an orbit never changes the framing's
// shape (the viewer fits the image to it, ui/display/image_rect.h).
TEST(OrbitCamera, MovesKeepTheSceneCamerasAspect) {
  CameraDesc wide = kBoxCamera;
  wide.aspectRatio = 1.5f;
  OrbitCamera orbit(wide, kBoxMin, kBoxMax);
  orbit.orbit(0.3f, 0.1f);
  orbit.zoom(2.f);
  orbit.fly({1.f, 0.f, 0.f}, 0.1f);
  ASSERT_TRUE(orbit.desc().aspectRatio.has_value());
  EXPECT_EQ(*orbit.desc().aspectRatio, 1.5f);
  EXPECT_FALSE(OrbitCamera(kBoxCamera, kBoxMin, kBoxMax).desc().aspectRatio.has_value());
}

// An orthographic scene camera stays orthographic; the wheel scales its magnification and keeps
// the distance (its rays start on its film plane) and a pan moves by its film's height.
TEST(OrbitCamera, AnOrthographicCameraZoomsByItsMagnification) {
  CameraDesc ortho = kBoxCamera;
  ortho.orthographic = Vec2(0.4f, 0.3f);
  OrbitCamera orbit(ortho, kBoxMin, kBoxMax);
  ASSERT_TRUE(orbit.desc().orthographic.has_value());
  const float before = orbit.distance();
  orbit.zoom(2.f);
  const float scale = 0.85f * 0.85f;
  EXPECT_FLOAT_EQ(orbit.distance(), before);  // the film plane stays where it was, out of the scene
  EXPECT_NEAR(orbit.desc().orthographic->x, 0.4f * scale, kEps);
  EXPECT_NEAR(orbit.desc().orthographic->y, 0.3f * scale, kEps);
  const Vec3 pivot = orbit.pivot();
  orbit.pan(0.f, 0.5f);  // half the image height up
  expectNear(orbit.pivot() - pivot, {0.f, 0.3f * scale, 0.f});
  EXPECT_FALSE(OrbitCamera(kBoxCamera, kBoxMin, kBoxMax).desc().orthographic.has_value());
}

TEST(OrbitCamera, OrbitKeepsTheDistanceAndAFullTurnReturns) {
  OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  const Vec3 pivot = orbit.pivot();
  for (int i = 0; i < 8; ++i) {
    orbit.orbit(2.f * kPi / 8.f, 0.f);
    EXPECT_NEAR(glm::length(orbit.eye() - pivot), orbit.distance(), kEps);
    expectNear(orbit.pivot(), pivot);
    // Still looking at the pivot.
    expectNear(orbit.eye() + orbit.distance() * orbit.forward(), pivot);
  }
  expectSameCamera(orbit.desc(), kBoxCamera);
  // Dragging right turns the eye to the camera's left (the scene turns with the cursor).
  OrbitCamera turned(kBoxCamera, kBoxMin, kBoxMax);
  const Vec3 left = -Vec3(kBoxCamera.cameraToWorld[0]);
  turned.orbit(0.1f, 0.f);
  EXPECT_GT(glm::dot(turned.eye() - Vec3(kBoxCamera.cameraToWorld[3]), left), 0.f);
}

TEST(OrbitCamera, PitchStopsShortOfThePole) {
  OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  orbit.orbit(0.f, 10.f);
  const CameraDesc d = orbit.desc();
  EXPECT_LT(orbit.forward().y, 1.f);
  EXPECT_NEAR(std::asin(orbit.forward().y), OrbitCamera::kMaxPitch, kEps);
  // The basis stays orthonormal and upright (no flip, no NaN).
  const Vec3 right(d.cameraToWorld[0]), up(d.cameraToWorld[1]);
  EXPECT_NEAR(glm::length(right), 1.f, kEps);
  EXPECT_NEAR(glm::dot(right, up), 0.f, kEps);
  EXPECT_NEAR(right.y, 0.f, kEps);
  EXPECT_GT(up.y, 0.f);
}

TEST(OrbitCamera, PanMovesEyeAndPivotTogether) {
  OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  const Vec3 eye = orbit.eye(), pivot = orbit.pivot();
  orbit.pan(0.5f, 0.f);
  const Vec3 moved = orbit.pivot() - pivot;
  expectNear(orbit.eye() - eye, moved);
  // Half an image height to the right at the pivot's distance.
  const float height = 2.f * orbit.distance() * std::tan(0.5f * kBoxCamera.yfov);
  expectNear(moved, 0.5f * height * Vec3(kBoxCamera.cameraToWorld[0]));
}

TEST(OrbitCamera, ZoomApproachesButNeverPassesThePivot) {
  OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  const float d0 = orbit.distance();
  orbit.zoom(1.f);
  EXPECT_NEAR(orbit.distance(), 0.85f * d0, kEps);
  orbit.zoom(-1.f);
  EXPECT_NEAR(orbit.distance(), d0, kEps);
  orbit.zoom(1000.f);
  EXPECT_GT(orbit.distance(), 0.f);
  EXPECT_GT(glm::dot(orbit.pivot() - orbit.eye(), orbit.forward()), 0.f);
}

TEST(OrbitCamera, FlyMovesAlongTheView) {
  OrbitCamera orbit(kBoxCamera, kBoxMin, kBoxMax);
  const Vec3 eye = orbit.eye();
  orbit.fly({1.f, 0.f, 0.f}, 0.5f);
  const Vec3 step = orbit.eye() - eye;
  EXPECT_GT(glm::dot(step, Vec3(0.f, 0.f, 1.f)), 0.f);
  EXPECT_NEAR(step.x, 0.f, kEps);
  EXPECT_NEAR(step.y, 0.f, kEps);
  expectSameCamera(OrbitCamera(kBoxCamera, kBoxMin, kBoxMax).desc(), kBoxCamera);  // reset = a fresh controller
}

}  // namespace
}  // namespace pathlab::ui
