// The camera as a sensor: a pinhole or a thin lens. Generates rays for film positions and, for
// light tracing, evaluates importance We and the densities of a given ray.
//
// Normalisation (pbrt-v3 sec. 16.1.1): We integrates to one over the film and the lens, so
//   We(p, w) = 1 / (A_film * A_lens * cos^4 theta),
// with A_film the area of the film rectangle at distance 1 from the lens and A_lens the lens area
// (1 for a pinhole, which is a delta in position). With a box filter, the value of pixel j is the
// mean radiance over its footprint; a light-tracing contribution splatted at raster position q
// therefore adds (number of pixels / number of light subpaths) x contribution to q's pixel.
#pragma once

#include "core/math/frame.h"
#include "core/math/ray.h"
#include "core/camera/camera_desc.h"

#include <optional>

namespace pathlab {

struct LensOptions {
  float apertureRadius = 0.f;  // 0: pinhole
  float focusDistance = 1.f;   // distance along the view axis of the plane in focus
  bool operator==(const LensOptions&) const = default;
};

struct CameraWiSample {
  Spectrum We{0.f};   // importance arriving at the reference point from the lens point
  Vec3 wi{0.f};       // from the reference point toward the lens point
  Vec3 pLens{0.f};
  Vec2 pRaster{0.f};  // where the contribution lands on the film, in pixels
  float dist = 0.f;
  // Solid angle at the reference point: dist^2 / (cos theta * A_lens). A pinhole is a delta in
  // position and counts as a lens of area 1 (pbrt-v3), so We / pdfW = We cos theta / dist^2.
  float pdfW = 0.f;
  float pdfDirW = 0.f;  // the camera's solid-angle density of the ray from pLens toward the reference (pdfWe)
};

struct CameraPdf {
  float pdfPosA = 0.f;  // lens area density (1 for a pinhole; orthographic: 1 / A_film on the film)
  float pdfDirW = 0.f;  // solid-angle density of the direction given the lens point (orthographic: 1, a delta)
};

class Camera {
 public:
  Camera() = default;
  Camera(const CameraDesc& desc, int width, int height, const LensOptions& lens = {});

  int width() const { return width_; }
  int height() const { return height_; }
  bool isPinhole() const { return lensRadius_ == 0.f && !orthographic_; }
  // Parallel rays from a film rectangle in the scene (glTF orthographic): the importance is a delta
  // in direction, like a directional light's emission. A camera subpath's first vertex is then
  // sampled by its position on the film, and no light subpath can connect to the camera (t = 1).
  bool isOrthographic() const { return orthographic_; }
  Vec3 position() const { return origin_; }
  Vec3 forward() const { return forward_; }

  // pRaster in pixels: (0,0) top-left of the image, (width,height) bottom-right.
  Ray generateRay(Vec2 pRaster, Vec2 uLens) const;
  // Importance of a ray leaving the lens at ray.o along ray.d; raster position through *pRaster.
  Spectrum We(const Ray& ray, Vec2* pRaster = nullptr) const;
  CameraPdf pdfWe(const Ray& ray) const;
  // Camera vertex for t = 1: a lens point seen from `ref`, with the importance it receives.
  std::optional<CameraWiSample> sampleWi(const Vec3& ref, Vec2 uLens) const;
  // Raster position of a world point through the lens centre (nullopt if behind or off film).
  std::optional<Vec2> rasterPosition(const Vec3& p) const;
  // The same in two steps for drawing segments that leave the film or pass behind the lens (the
  // path inspector clips them): a world point in camera space (looking down -z), and the raster
  // position of a camera-space point in front of the lens (depth -z > 0), on the film or not.
  Vec3 toCameraSpace(const Vec3& p) const { return Vec3(worldToCamera_ * Vec4(p, 1.f)); }
  Vec2 rasterOfCameraPoint(const Vec3& pCam) const {
    return filmToRaster(orthographic_ ? Vec2(pCam) : Vec2(pCam) / -pCam.z);
  }

 private:
  Mat4 cameraToWorld_{1.f}, worldToCamera_{1.f};
  Vec3 origin_{0.f}, forward_{0.f, 0.f, -1.f};
  int width_ = 1, height_ = 1;
  // Film half-extent at distance 1; orthographic: in world units on the film plane.
  float tanHalfY_ = 0.5f, tanHalfX_ = 0.5f;
  float filmArea_ = 1.f;  // A_film at distance 1 (orthographic: the film rectangle's area)
  bool orthographic_ = false;
  float lensRadius_ = 0.f, focusDistance_ = 1.f;

  float lensArea() const;
  // We, the directional density and the raster position of a ray leaving the lens, in one
  // evaluation; nullopt off the film.
  struct RayImportance {
    float We = 0.f, pdfDirW = 0.f;
    Vec2 pRaster{0.f};
  };
  std::optional<RayImportance> importance(const Ray& ray) const;  // A_lens: pi r^2, or 1 for the pinhole's delta
  // Film plane at distance 1 (camera space x, y) <-> raster pixels.
  Vec2 filmToRaster(Vec2 pFilm) const;
  Vec2 rasterToFilm(Vec2 pRaster) const;
  bool onFilm(Vec2 pRaster) const;
  // Where a camera-space ray from the lens plane lands on the film, through the focal plane.
  std::optional<Vec2> rasterOfCameraRay(const Vec3& oCam, const Vec3& dCam) const;
};

// Frame the scene's bounds when the file has no camera: a three-quarter view (from the front
// right and above, kFrameDirection, +y up as in glTF) of the centre, from far enough that the
// bounding sphere fits the vertical field of view. Neither a flat model facing +z nor one lying
// in the xz plane is then seen edge-on.
constexpr Vec3 kFrameDirection{0.5198f, 0.4226f, 0.7424f};  // azimuth 35 deg from +z, elevation 25 deg
CameraDesc frameBounds(const Vec3& boundsMin, const Vec3& boundsMax, float yfov = 0.6911f);

}  // namespace pathlab
