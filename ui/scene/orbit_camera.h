// The viewer's camera controller: orbit about a pivot, pan, zoom (dolly) and WASD fly, producing
// the CameraDesc that overrides the scene's camera (RenderSettings::camera). Pure math, no input.
//
// State: a pivot, the eye's distance to it and the view direction as yaw and pitch about the
// world's +y (glTF's up). A scene camera with roll loses it on the first move.
#pragma once

#include "core/scene/scene_desc.h"

#include <optional>

namespace pathlab::ui {

class OrbitCamera {
 public:
  OrbitCamera() = default;
  // Starts from the scene's camera; the pivot is the point on the view axis nearest the centre
  // of the scene's bounds (half the bounds' diagonal ahead when the centre is behind the eye).
  OrbitCamera(const CameraDesc& scene, const Vec3& boundsMin, const Vec3& boundsMax);

  // Rotates the eye about the pivot: yaw about world +y, pitch about the camera's right axis
  // (kept within +-kMaxPitch so the view never flips over the pole).
  void orbit(float yawRadians, float pitchRadians);
  // Moves eye and pivot in the image plane; dx, dy are fractions of the image height.
  void pan(float dx, float dy);
  // Dolly toward the pivot: each step scales the distance by 0.85 (negative steps move away).
  void zoom(float steps);
  // Moves eye and pivot: forward / right / up in units of the fly speed (scene size per second).
  void fly(const Vec3& forwardRightUp, float seconds);

  CameraDesc desc() const;
  Vec3 eye() const;
  Vec3 forward() const;
  Vec3 pivot() const { return pivot_; }
  float distance() const { return distance_; }

  static constexpr float kMaxPitch = 1.5533f;  // 89 degrees

 private:
  Vec3 pivot_{0.f};
  float distance_ = 1.f;
  float yaw_ = 0.f, pitch_ = 0.f;  // forward (0,0) = -z
  float yfov_ = 0.6911f;
  // The scene camera's: an orbit or a fly never changes the framing's shape (ui/display/image_rect.h).
  std::optional<float> aspectRatio_;
  // An orthographic scene camera stays one: the wheel scales its magnification and keeps the
  // distance (a dolly would change nothing but where its rays start), a pan moves by its film's height.
  std::optional<Vec2> orthographic_;
  float flySpeed_ = 1.f;
  float minDistance_ = 1e-3f;
};

}  // namespace pathlab::ui
