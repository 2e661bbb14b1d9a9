// Pinhole and thin-lens camera: ray generation, importance We and its densities (see camera.h).
#include "core/camera/camera.h"

#include "core/sampling/warp.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace pathlab {

Camera::Camera(const CameraDesc& desc, int width, int height, const LensOptions& lens)
    : width_(width), height_(height) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("camera '" + desc.name + "': image size must be positive, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  // Keep only rotation and translation: a glTF camera node may carry scale or shear, which would
  // otherwise leak into ray directions and the lens.
  const Mat4& m = desc.cameraToWorld;
  origin_ = Vec3(m[3]);
  forward_ = glm::normalize(-Vec3(m[2]));
  Vec3 right = glm::cross(forward_, Vec3(m[1]));
  right = glm::dot(right, right) > 0.f ? glm::normalize(right) : Frame(-forward_).s;
  const Vec3 up = glm::cross(right, forward_);
  cameraToWorld_ = Mat4(Vec4(right, 0.f), Vec4(up, 0.f), Vec4(-forward_, 0.f), Vec4(origin_, 1.f));
  worldToCamera_ = glm::inverse(cameraToWorld_);

  // The film aspect is the image's; the vertical field of view (or the film's height) is the file's.
  if (desc.orthographic) {
    if (!(desc.orthographic->x > 0.f) || !(desc.orthographic->y > 0.f) || !std::isfinite(desc.orthographic->y))
      throw std::invalid_argument("camera '" + desc.name + "': an orthographic camera needs xmag and ymag > 0");
    if (lens.apertureRadius > 0.f)
      throw std::invalid_argument("camera '" + desc.name +
                                  "': an orthographic camera has no lens (its rays are parallel): set no aperture");
    orthographic_ = true;
    tanHalfY_ = desc.orthographic->y;
  } else {
    tanHalfY_ = std::tan(0.5f * glm::clamp(desc.yfov, 1e-4f, kPi - 1e-4f));
  }
  tanHalfX_ = tanHalfY_ * static_cast<float>(width) / static_cast<float>(height);
  filmArea_ = 4.f * tanHalfX_ * tanHalfY_;
  lensRadius_ = std::max(lens.apertureRadius, 0.f);
  focusDistance_ = std::max(lens.focusDistance, 1e-4f);
}

// A pinhole (and an orthographic camera, whose position density is the film's) counts as a lens of area 1.
float Camera::lensArea() const { return lensRadius_ == 0.f ? 1.f : kPi * lensRadius_ * lensRadius_; }

Vec2 Camera::rasterToFilm(Vec2 pRaster) const {
  return {(2.f * pRaster.x / static_cast<float>(width_) - 1.f) * tanHalfX_,
          (1.f - 2.f * pRaster.y / static_cast<float>(height_)) * tanHalfY_};
}

Vec2 Camera::filmToRaster(Vec2 pFilm) const {
  return {0.5f * (pFilm.x / tanHalfX_ + 1.f) * static_cast<float>(width_),
          0.5f * (1.f - pFilm.y / tanHalfY_) * static_cast<float>(height_)};
}

bool Camera::onFilm(Vec2 pRaster) const {
  // Half-open, so that a splat's pixel index floor(pRaster) is always inside the image.
  return pRaster.x >= 0.f && pRaster.y >= 0.f && pRaster.x < static_cast<float>(width_) &&
         pRaster.y < static_cast<float>(height_);
}

std::optional<Vec2> Camera::rasterOfCameraRay(const Vec3& oCam, const Vec3& dCam) const {
  const float cosTheta = -dCam.z;
  if (!(cosTheta > 0.f)) return std::nullopt;
  Vec2 pFilm;
  if (isPinhole()) {
    pFilm = Vec2(dCam) / cosTheta;
  } else {
    // Every ray through a point of the focal plane maps to where the lens centre sees it.
    const float t = (focusDistance_ + oCam.z) / cosTheta;
    if (!(t > 0.f)) return std::nullopt;
    pFilm = Vec2(oCam + t * dCam) / focusDistance_;
  }
  const Vec2 pRaster = filmToRaster(pFilm);
  if (!onFilm(pRaster)) return std::nullopt;
  return pRaster;
}

Ray Camera::generateRay(Vec2 pRaster, Vec2 uLens) const {
  if (orthographic_) {
    Ray ray;
    ray.o = Vec3(cameraToWorld_ * Vec4(rasterToFilm(pRaster), 0.f, 1.f));
    ray.d = forward_;
    return ray;
  }
  const Vec3 pFilm(rasterToFilm(pRaster), -1.f);
  Vec3 pLens(0.f), d;
  if (isPinhole()) {
    d = glm::normalize(pFilm);
  } else {
    pLens = Vec3(lensRadius_ * sampleUniformDiskConcentric(uLens), 0.f);
    d = glm::normalize(pFilm * focusDistance_ - pLens);
  }
  Ray ray;
  ray.o = Vec3(cameraToWorld_ * Vec4(pLens, 1.f));
  ray.d = glm::normalize(Mat3(cameraToWorld_) * d);
  return ray;
}

std::optional<Camera::RayImportance> Camera::importance(const Ray& ray) const {
  // ray.o is taken to lie on the lens (the origin for a pinhole), as every camera vertex does.
  const Vec3 dCam = glm::normalize(Mat3(worldToCamera_) * ray.d);
  const Vec3 oCam = isPinhole() ? Vec3(0.f) : Vec3(worldToCamera_ * Vec4(ray.o, 1.f));
  const std::optional<Vec2> raster = rasterOfCameraRay(oCam, dCam);
  if (!raster) return std::nullopt;
  const float cos2 = dCam.z * dCam.z;
  const float cosTheta = -dCam.z;
  RayImportance r;
  r.pRaster = *raster;
  // pbrt-v3 eq. 16.3: normalised so that the integral over film and lens of We cos is one.
  r.We = 1.f / (filmArea_ * lensArea() * cos2 * cos2);
  // Uniform on the film plane at distance 1 (area A_film), converted to solid angle:
  // dA = dw / cos^3 (distance 1/cos, foreshortening cos).
  r.pdfDirW = 1.f / (filmArea_ * cosTheta * cosTheta * cosTheta);
  return r;
}

Spectrum Camera::We(const Ray& ray, Vec2* pRaster) const {
  // An orthographic camera's importance is a delta in direction: no given ray evaluates it.
  if (orthographic_) return Spectrum(0.f);
  const std::optional<RayImportance> r = importance(ray);
  if (!r) return Spectrum(0.f);
  if (pRaster) *pRaster = r->pRaster;
  return Spectrum(r->We);
}

CameraPdf Camera::pdfWe(const Ray& ray) const {
  if (orthographic_) {
    // Uniform over the film rectangle; the direction is the view axis (a delta, counted as one).
    const Vec2 pRaster = filmToRaster(Vec2(worldToCamera_ * Vec4(ray.o, 1.f)));
    if (!onFilm(pRaster) || glm::dot(ray.d, forward_) < 1.f - 1e-5f) return {};
    return {1.f / filmArea_, 1.f};
  }
  const std::optional<RayImportance> r = importance(ray);
  if (!r) return {};
  return {1.f / lensArea(), r->pdfDirW};
}

std::optional<CameraWiSample> Camera::sampleWi(const Vec3& ref, Vec2 uLens) const {
  if (orthographic_) return std::nullopt;  // no point can see it along a direction of its choosing
  // A pinhole's lens point is the camera's origin: no transform.
  const Vec3 pLens = isPinhole()
                         ? origin_
                         : Vec3(cameraToWorld_ * Vec4(lensRadius_ * sampleUniformDiskConcentric(uLens), 0.f, 1.f));
  const Vec3 toLens = pLens - ref;
  const float dist2 = glm::dot(toLens, toLens);
  if (!(dist2 > 0.f)) return std::nullopt;
  CameraWiSample s;
  const float invDist = 1.f / std::sqrt(dist2);
  s.dist = dist2 * invDist;
  s.wi = toLens * invDist;
  s.pLens = pLens;
  float cosTheta = 0.f;
  if (isPinhole()) {
    // The pinhole in one pass (light tracing evaluates it for every light vertex): the camera
    // space direction toward ref is a rotation of the unit -wi (cameraToWorld_ is rigid), and
    // its film point, We and pdfWe share one cosine; the same quantities as importance().
    const Vec3 dCam = Mat3(worldToCamera_) * -s.wi;
    cosTheta = -dCam.z;
    if (!(cosTheta > 0.f)) return std::nullopt;
    s.pRaster = filmToRaster(Vec2(dCam) * (1.f / cosTheta));
    if (!onFilm(s.pRaster)) return std::nullopt;
    const float We = 1.f / (filmArea_ * (cosTheta * cosTheta) * (cosTheta * cosTheta));  // lens area 1
    s.We = Spectrum(We);
    s.pdfDirW = We * cosTheta;  // 1 / (A_film cos^3)
  } else {
    // One evaluation gives the importance, the raster position and the camera's own directional
    // density of this ray, which the MIS weight of the t = 1 technique needs (pdfDirW).
    const std::optional<RayImportance> r = importance(Ray{pLens, -s.wi});
    if (!r) return std::nullopt;
    s.We = Spectrum(r->We);
    s.pRaster = r->pRaster;
    s.pdfDirW = r->pdfDirW;
    cosTheta = glm::dot(-s.wi, forward_);
  }
  // Lens area density to solid angle at ref (pbrt-v3 PerspectiveCamera::Sample_Wi); a pinhole
  // counts as a lens of area 1, so We / pdfW = We cos / dist^2 there.
  s.pdfW = dist2 / (cosTheta * lensArea());
  if (!std::isfinite(s.pdfW) || !(s.pdfW > 0.f)) return std::nullopt;
  return s;
}

std::optional<Vec2> Camera::rasterPosition(const Vec3& p) const {
  const Vec3 pCam = Vec3(worldToCamera_ * Vec4(p, 1.f));
  const float depth = -pCam.z;
  if (!(depth > 0.f)) return std::nullopt;
  const Vec2 pRaster = rasterOfCameraPoint(pCam);
  if (!onFilm(pRaster)) return std::nullopt;
  return pRaster;
}

CameraDesc frameBounds(const Vec3& boundsMin, const Vec3& boundsMax, float yfov) {
  const Vec3 center = 0.5f * (boundsMin + boundsMax);
  float radius = 0.5f * glm::length(boundsMax - boundsMin);
  if (!(radius > 0.f) || !std::isfinite(radius)) radius = 1.f;
  // The sphere is tangent to the view cone at distance radius / sin(yfov / 2); 10% margin.
  const float distance = radius / std::sin(0.5f * yfov) * 1.1f;
  // The camera looks down its -z: z points from the centre to the eye; x = up x z, y = z x x.
  const Vec3 z = glm::normalize(kFrameDirection);
  const Vec3 x = glm::normalize(glm::cross(Vec3(0.f, 1.f, 0.f), z));
  const Vec3 y = glm::cross(z, x);
  CameraDesc desc;
  desc.cameraToWorld = Mat4(Vec4(x, 0.f), Vec4(y, 0.f), Vec4(z, 0.f), Vec4(center + distance * z, 1.f));
  desc.yfov = yfov;
  desc.name = "frameBounds";
  return desc;
}

}  // namespace pathlab
