// Orbit / pan / zoom / fly camera controller (see orbit_camera.h).
#include "ui/scene/orbit_camera.h"

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

namespace {

Vec3 directionOf(float yaw, float pitch) {
  return {std::sin(yaw) * std::cos(pitch), std::sin(pitch), -std::cos(yaw) * std::cos(pitch)};
}

// Right and up of a view direction with world +y up (forward is never vertical: pitch is clamped).
void basisOf(const Vec3& forward, Vec3& right, Vec3& up) {
  right = glm::normalize(glm::cross(forward, Vec3(0.f, 1.f, 0.f)));
  up = glm::cross(right, forward);
}

}  // namespace

OrbitCamera::OrbitCamera(const CameraDesc& scene, const Vec3& boundsMin, const Vec3& boundsMax) {
  const Mat4& m = scene.cameraToWorld;
  const Vec3 eye(m[3]);
  const Vec3 f = glm::normalize(-Vec3(m[2]));
  pitch_ = std::clamp(std::asin(std::clamp(f.y, -1.f, 1.f)), -kMaxPitch, kMaxPitch);
  yaw_ = std::atan2(f.x, -f.z);
  yfov_ = scene.yfov;
  aspectRatio_ = scene.aspectRatio;
  orthographic_ = scene.orthographic;
  const float diagonal = std::max(glm::length(boundsMax - boundsMin), 1e-3f);
  const float ahead = glm::dot(0.5f * (boundsMin + boundsMax) - eye, f);
  distance_ = ahead > 1e-3f * diagonal ? ahead : 0.5f * diagonal;
  pivot_ = eye + distance_ * directionOf(yaw_, pitch_);
  flySpeed_ = 0.5f * diagonal;
  minDistance_ = 1e-4f * diagonal;
}

Vec3 OrbitCamera::forward() const { return directionOf(yaw_, pitch_); }
Vec3 OrbitCamera::eye() const { return pivot_ - distance_ * forward(); }

void OrbitCamera::orbit(float yawRadians, float pitchRadians) {
  yaw_ = std::remainder(yaw_ + yawRadians, 2.f * kPi);
  pitch_ = std::clamp(pitch_ + pitchRadians, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(float dx, float dy) {
  Vec3 right, up;
  basisOf(forward(), right, up);
  // A fraction of the image height at the pivot's distance, so the pivot follows the cursor.
  const float height = orthographic_ ? 2.f * orthographic_->y : 2.f * distance_ * std::tan(0.5f * yfov_);
  pivot_ += height * (dx * right + dy * up);
}

void OrbitCamera::zoom(float steps) {
  // An orthographic view zooms by its magnification alone: moving its film plane (where its
  // parallel rays start) toward the pivot would cut away the scene in front of it.
  if (orthographic_) {
    *orthographic_ *= std::pow(0.85f, steps);
    return;
  }
  distance_ = std::max(distance_ * std::pow(0.85f, steps), minDistance_);
}

void OrbitCamera::fly(const Vec3& forwardRightUp, float seconds) {
  Vec3 right, up;
  basisOf(forward(), right, up);
  pivot_ += flySpeed_ * seconds * (forwardRightUp.x * forward() + forwardRightUp.y * right + forwardRightUp.z * up);
}

CameraDesc OrbitCamera::desc() const {
  Vec3 right, up;
  const Vec3 f = forward();
  basisOf(f, right, up);
  CameraDesc d;
  d.cameraToWorld = Mat4(Vec4(right, 0.f), Vec4(up, 0.f), Vec4(-f, 0.f), Vec4(eye(), 1.f));
  d.yfov = yfov_;
  d.aspectRatio = aspectRatio_;
  d.orthographic = orthographic_;
  d.name = "viewer";
  return d;
}

}  // namespace pathlab::ui
