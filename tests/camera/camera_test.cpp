// Tests of the pinhole and thin-lens camera: raster <-> ray round trips, the normalisation of
// We, its densities against the raster density, sampleWi and focusing.
#include "core/camera/camera.h"
#include "core/math/rng.h"
#include "core/sampling/warp.h"
#include "tests/support/chi2.h"

#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

namespace pathlab {
namespace {

using Estimate = test::RunningStats;

constexpr int kWidth = 64, kHeight = 48;
constexpr float kYfov = 0.8f;
const Vec3 kEye(1.f, 2.f, 3.f), kTarget(-1.f, 0.5f, -2.f), kUp(0.1f, 1.f, 0.f);

// A camera placed by lookAt, with a scale in its matrix that the camera must ignore, and a glTF
// aspect ratio that disagrees with the image's (the image wins).
CameraDesc makeDesc() {
  CameraDesc desc;
  desc.cameraToWorld = glm::inverse(glm::lookAt(kEye, kTarget, kUp)) * glm::scale(Mat4(1.f), Vec3(2.f));
  desc.yfov = kYfov;
  desc.aspectRatio = 2.5f;
  return desc;
}

Camera pinhole() { return Camera(makeDesc(), kWidth, kHeight); }
Camera thinLens() { return Camera(makeDesc(), kWidth, kHeight, LensOptions{0.25f, 4.f}); }

float tanHalfY() { return std::tan(0.5f * kYfov); }
float tanHalfX() { return tanHalfY() * kWidth / kHeight; }
float filmArea() { return 4.f * tanHalfX() * tanHalfY(); }

TEST(CameraRay, RasterRayRasterRoundTrip) {
  Pcg32 rng(1, 2);
  for (const Camera& camera : {pinhole(), thinLens()}) {
    const float focus = camera.isPinhole() ? 1.f : 4.f;
    for (int k = 0; k < 5000; ++k) {
      const Vec2 raster(rng.next1D() * kWidth, rng.next1D() * kHeight);
      const Ray ray = camera.generateRay(raster, rng.next2D());
      EXPECT_NEAR(glm::length(ray.d), 1.f, 1e-5f);
      EXPECT_LE(glm::length(ray.o - camera.position()), 0.25f + 1e-5f);
      Vec2 back(-1.f);
      ASSERT_GT(camera.We(ray, &back).r, 0.f);
      EXPECT_NEAR(back.x, raster.x, 1e-3f);
      EXPECT_NEAR(back.y, raster.y, 1e-3f);
      // The point where the ray crosses the plane of focus projects back through the lens centre.
      const float t = focus / glm::dot(ray.d, camera.forward());
      const std::optional<Vec2> projected = camera.rasterPosition(ray.o + t * ray.d);
      ASSERT_TRUE(projected);
      EXPECT_NEAR(projected->x, raster.x, 1e-3f);
      EXPECT_NEAR(projected->y, raster.y, 1e-3f);
    }
  }
}

TEST(CameraRay, OrientationAndCentre) {
  const Camera camera = pinhole();
  const Vec3 forward = glm::normalize(kTarget - kEye);
  const Vec3 right = glm::normalize(glm::cross(forward, kUp));
  const Vec3 up = glm::cross(right, forward);
  EXPECT_NEAR(glm::dot(camera.forward(), forward), 1.f, 1e-6f);
  EXPECT_NEAR(glm::length(camera.position() - kEye), 0.f, 1e-5f);
  const Ray centre = camera.generateRay(Vec2(kWidth, kHeight) * 0.5f, Vec2(0.5f));
  EXPECT_NEAR(glm::dot(centre.d, forward), 1.f, 1e-6f);
  // Raster (0,0) is the top-left corner; the film is as wide as the image's aspect says.
  const Ray corner = camera.generateRay(Vec2(0.f), Vec2(0.5f));
  const float c = glm::dot(corner.d, forward);
  EXPECT_NEAR(glm::dot(corner.d, up) / c, tanHalfY(), 1e-5f);
  EXPECT_NEAR(glm::dot(corner.d, right) / c, -tanHalfX(), 1e-5f);
  // Thin lens: every ray through the image centre passes through the focus point on the axis.
  const Camera lens = thinLens();
  Pcg32 rng(3, 4);
  for (int k = 0; k < 100; ++k) {
    const Ray r = lens.generateRay(Vec2(kWidth, kHeight) * 0.5f, rng.next2D());
    const float t = 4.f / glm::dot(r.d, forward);
    EXPECT_NEAR(glm::length(r.o + t * r.d - (kEye + 4.f * forward)), 0.f, 1e-4f);
  }
}

TEST(CameraRay, ThinLensFocuses) {
  const Camera camera = thinLens();
  Pcg32 rng(5, 6);
  for (int k = 0; k < 50; ++k) {
    const Vec2 raster(rng.next1D() * kWidth, rng.next1D() * kHeight);
    std::optional<Vec3> meet;
    for (int j = 0; j < 50; ++j) {
      const Ray r = camera.generateRay(raster, rng.next2D());
      // Intersection with the plane of focus, dot(p - eye, forward) = 4.
      const float t = (4.f - glm::dot(r.o - camera.position(), camera.forward())) /
                      glm::dot(r.d, camera.forward());
      const Vec3 p = r.o + t * r.d;
      if (!meet) meet = p;
      EXPECT_NEAR(glm::length(p - *meet), 0.f, 2e-5f * 4.f);
    }
  }
}

TEST(CameraImportance, PdfWeOfGeneratedRays) {
  Pcg32 rng(7, 8);
  for (const Camera& camera : {pinhole(), thinLens()}) {
    const float lensArea = camera.isPinhole() ? 1.f : kPi * 0.25f * 0.25f;
    for (int k = 0; k < 2000; ++k) {
      const Vec2 raster(rng.next1D() * kWidth, rng.next1D() * kHeight);
      const Ray ray = camera.generateRay(raster, rng.next2D());
      const float cosTheta = glm::dot(ray.d, camera.forward());
      const CameraPdf pdf = camera.pdfWe(ray);
      EXPECT_NEAR(pdf.pdfPosA, 1.f / lensArea, 1e-5f / lensArea);
      const float expected = 1.f / (filmArea() * cosTheta * cosTheta * cosTheta);
      EXPECT_NEAR(pdf.pdfDirW, expected, 1e-4f * expected);
      const float we = camera.We(ray).r;
      EXPECT_NEAR(we, 1.f / (filmArea() * lensArea * sqr(sqr(cosTheta))), 1e-4f * we);
    }
    // Behind the camera or outside the field of view: no importance, no density.
    const Ray backward{camera.position(), -camera.forward()};
    EXPECT_EQ(camera.We(backward), Spectrum(0.f));
    EXPECT_EQ(camera.pdfWe(backward).pdfDirW, 0.f);
    const Frame f(camera.forward());
    const Ray outside{camera.position(), glm::normalize(camera.forward() + 2.f * f.s)};
    EXPECT_EQ(camera.We(outside), Spectrum(0.f));
    EXPECT_EQ(camera.pdfWe(outside).pdfPosA, 0.f);
  }
}

TEST(CameraImportance, DirectionalPdfIsTheRasterDensity) {
  // Uniform raster positions induce a density in solid angle of 1 / (W H |dw / dpixel^2|); the
  // Jacobian comes from central differences of generateRay with a fixed lens point.
  Pcg32 rng(9, 10);
  const float h = 0.25f;
  for (const Camera& camera : {pinhole(), thinLens()}) {
    for (int k = 0; k < 200; ++k) {
      const Vec2 raster(h + rng.next1D() * (kWidth - 2 * h), h + rng.next1D() * (kHeight - 2 * h));
      const Vec2 uLens = rng.next2D();
      const auto dir = [&](Vec2 p) { return DVec3(camera.generateRay(p, uLens).d); };
      const DVec3 dx = (dir(raster + Vec2(h, 0.f)) - dir(raster - Vec2(h, 0.f))) / (2.0 * h);
      const DVec3 dy = (dir(raster + Vec2(0.f, h)) - dir(raster - Vec2(0.f, h))) / (2.0 * h);
      const double solidAnglePerPixel = glm::length(glm::cross(dx, dy));
      const double density = 1.0 / (kWidth * kHeight * solidAnglePerPixel);
      const float pdf = camera.pdfWe(camera.generateRay(raster, uLens)).pdfDirW;
      EXPECT_NEAR(pdf, density, 2e-3 * density);
    }
  }
}

TEST(CameraImportance, IntegratesToOneOverFilmAndLens) {
  // integral over lens and directions of We cos theta = 1 (pbrt-v3 sec. 16.1.1). Directions
  // uniform in a cone about forward that covers the film as seen from every lens point.
  Pcg32 rng(11, 12);
  for (const Camera& camera : {pinhole(), thinLens()}) {
    const float r = camera.isPinhole() ? 0.f : 0.25f, focus = 4.f;
    const float diagonal = std::sqrt(sqr(tanHalfX()) + sqr(tanHalfY()));
    const float cosMax = std::cos(std::atan(diagonal + r / focus) * 1.02f);
    const Frame f(camera.forward());
    const Vec3 right = glm::normalize(glm::cross(camera.forward(), kUp));
    const Vec3 up = glm::cross(right, camera.forward());
    const double lensPdf = camera.isPinhole() ? 1.0 : 1.0 / (kPi * r * r);
    Estimate e;
    for (int k = 0; k < 400000; ++k) {
      const Vec2 d = r * sampleUniformDiskConcentric(rng.next2D());
      const Vec3 o = camera.position() + d.x * right + d.y * up;
      const Vec3 w = f.toWorld(sampleUniformCone(rng.next2D(), cosMax));
      const double cosTheta = glm::dot(w, camera.forward());
      e.add(camera.We(Ray{o, w}).r * cosTheta / (lensPdf * uniformConePdf(cosMax)));
    }
    EXPECT_NEAR(e.mean(), 1.0, 4 * e.standardError()) << (camera.isPinhole() ? "pinhole" : "thin lens");
    EXPECT_LT(e.standardError(), 0.01);
  }
}

TEST(CameraWi, SampleWiAgreesWithWe) {
  Pcg32 rng(13, 14);
  for (const Camera& camera : {pinhole(), thinLens()}) {
    const float lensArea = camera.isPinhole() ? 1.f : kPi * 0.25f * 0.25f;
    int found = 0;
    for (int k = 0; k < 3000; ++k) {
      // Points in front of the camera, some off the film.
      const Vec2 raster(rng.next1D() * kWidth * 1.4f - 0.2f * kWidth,
                        rng.next1D() * kHeight * 1.4f - 0.2f * kHeight);
      const float depth = 0.5f + 8.f * rng.next1D();
      const Ray through = camera.generateRay(raster, Vec2(0.5f));  // through the lens centre
      const Vec3 ref = through.o + through.d * (depth / glm::dot(through.d, camera.forward()));
      const std::optional<CameraWiSample> s = camera.sampleWi(ref, rng.next2D());
      if (!s) continue;
      ++found;
      EXPECT_NEAR(glm::length(s->pLens - ref), s->dist, 1e-5f * s->dist);
      EXPECT_NEAR(glm::dot(s->wi, glm::normalize(s->pLens - ref)), 1.f, 1e-6f);
      EXPECT_LE(glm::length(s->pLens - camera.position()), 0.25f + 1e-5f);
      Vec2 pRaster;
      const Spectrum we = camera.We(Ray{s->pLens, -s->wi}, &pRaster);
      EXPECT_NEAR(s->We.r, we.r, 1e-5f * we.r);
      // The directional density the t = 1 technique's MIS weight takes from the same evaluation.
      const float pdfDirW = camera.pdfWe(Ray{s->pLens, -s->wi}).pdfDirW;
      EXPECT_NEAR(s->pdfDirW, pdfDirW, 1e-5f * pdfDirW);
      EXPECT_NEAR(s->pRaster.x, pRaster.x, 1e-3f);
      EXPECT_NEAR(s->pRaster.y, pRaster.y, 1e-3f);
      const float cosTheta = glm::dot(-s->wi, camera.forward());
      const float expected = sqr(s->dist) / (cosTheta * lensArea);
      EXPECT_NEAR(s->pdfW, expected, 1e-5f * expected);
      if (camera.isPinhole()) {
        const std::optional<Vec2> projected = camera.rasterPosition(ref);
        ASSERT_TRUE(projected);
        EXPECT_NEAR(s->pRaster.x, projected->x, 1e-3f);
        EXPECT_NEAR(s->pRaster.y, projected->y, 1e-3f);
      }
    }
    EXPECT_GT(found, 1000);
    EXPECT_FALSE(camera.sampleWi(camera.position() - camera.forward(), Vec2(0.5f)));
  }
  // A point on the plane of focus lands on the same raster position from every lens point.
  const Camera camera = thinLens();
  const Ray through = camera.generateRay(Vec2(10.f, 30.f), Vec2(0.5f));
  const Vec3 ref = through.o + through.d * (4.f / glm::dot(through.d, camera.forward()));
  for (int k = 0; k < 100; ++k) {
    const std::optional<CameraWiSample> s = camera.sampleWi(ref, rng.next2D());
    ASSERT_TRUE(s);
    EXPECT_NEAR(s->pRaster.x, 10.f, 1e-3f);
    EXPECT_NEAR(s->pRaster.y, 30.f, 1e-3f);
  }
}

TEST(CameraWi, ThinLensDirectionsChi2) {
  // From a point close to the lens the aperture covers a wide cone; the point is near the plane
  // of focus so every lens point sees it on the film.
  CameraDesc desc;  // at the origin looking down -z, so the lens faces +z in world space
  const Camera camera(desc, kWidth, kHeight, LensOptions{0.5f, 0.3f});
  const Vec3 ref(0.01f, -0.02f, -0.35f);
  const auto sample = [&](Pcg32& rng) -> std::optional<Vec3> {
    const std::optional<CameraWiSample> s = camera.sampleWi(ref, rng.next2D());
    if (!s) return std::nullopt;
    return s->wi;
  };
  const auto pdf = [&](const Vec3& w) -> double {
    if (!(w.z > 0.f)) return 0.0;
    const float t = -ref.z / w.z;  // to the lens plane z = 0
    const Vec3 p = ref + t * w;
    if (glm::length(Vec2(p)) > 0.5f) return 0.0;
    return sqr(t) / (w.z * kPi * 0.25f);
  };
  const test::Chi2Result r = test::chi2SphereTest(sample, pdf, 20, 40, 200000, 15);
  EXPECT_TRUE(r.passed) << r.message;
}

// glTF's orthographic camera (issue 15): parallel rays along the view axis from a film rectangle
// of 2 xmag x 2 ymag (the image's aspect sets the width), uniform over it; a delta in direction,
// so no point can connect to it (t = 1) and no given ray carries importance.
TEST(OrthographicCamera, ParallelRaysFromTheFilmRectangle) {
  CameraDesc desc;
  desc.name = "ortho";
  desc.cameraToWorld = glm::translate(Mat4(1.f), Vec3(1.f, 2.f, 5.f));  // looks down -z
  desc.orthographic = Vec2(2.f, 1.f);
  const Camera camera(desc, 200, 100);
  EXPECT_TRUE(camera.isOrthographic());
  EXPECT_FALSE(camera.isPinhole());
  const Vec2 raster[] = {{0.f, 0.f}, {200.f, 100.f}, {100.f, 50.f}, {150.f, 25.f}};
  const Vec3 origin[] = {{-1.f, 3.f, 5.f}, {3.f, 1.f, 5.f}, {1.f, 2.f, 5.f}, {2.f, 2.5f, 5.f}};
  for (int i = 0; i < 4; ++i) {
    const Ray ray = camera.generateRay(raster[i], Vec2(0.3f, 0.8f));
    EXPECT_NEAR(glm::distance(ray.o, origin[i]), 0.f, 1e-5f) << i;
    EXPECT_NEAR(glm::distance(ray.d, Vec3(0.f, 0.f, -1.f)), 0.f, 1e-6f) << i;
    if (i >= 2) {
      const CameraPdf pdf = camera.pdfWe(ray);
      EXPECT_FLOAT_EQ(pdf.pdfPosA, 1.f / 8.f);  // 1 / (4 xmag ymag)
      EXPECT_FLOAT_EQ(pdf.pdfDirW, 1.f);        // the delta, counted as one
      EXPECT_EQ(camera.We(ray), Spectrum(0.f));
      // A point straight ahead of the ray lands where the ray started.
      const std::optional<Vec2> back = camera.rasterPosition(ray.o + 3.f * ray.d);
      ASSERT_TRUE(back.has_value());
      EXPECT_NEAR(glm::distance(*back, raster[i]), 0.f, 1e-3f);
    }
  }
  const Ray slanted{Vec3(1.f, 2.f, 5.f), glm::normalize(Vec3(0.1f, 0.f, -1.f))};
  EXPECT_EQ(camera.pdfWe(slanted).pdfPosA, 0.f);
  EXPECT_FALSE(camera.sampleWi(Vec3(1.f, 2.f, 0.f), Vec2(0.5f)).has_value());
  EXPECT_THROW(Camera(desc, 200, 100, LensOptions{0.1f, 2.f}), std::invalid_argument);
  desc.orthographic = Vec2(1.f, 0.f);
  EXPECT_THROW(Camera(desc, 200, 100), std::invalid_argument);
}

TEST(CameraFrame, FrameBoundsFitsTheSphere) {
  const Vec3 lo(-1.f, 0.f, 2.f), hi(3.f, 1.f, 4.f);
  const float yfov = 0.6911f;
  const CameraDesc desc = frameBounds(lo, hi);
  const Vec3 centre = 0.5f * (lo + hi);
  const float radius = 0.5f * glm::length(hi - lo);
  const Camera camera(desc, 100, 100);
  // A three-quarter view: from the front right and above, image up toward +y.
  const Vec3 view = camera.forward();
  EXPECT_NEAR(glm::length(view), 1.f, 1e-6f);
  EXPECT_LT(view.x, -0.3f);
  EXPECT_LT(view.y, -0.3f);
  EXPECT_LT(view.z, -0.5f);
  EXPECT_GT(desc.cameraToWorld[1].y, 0.8f);  // camera +y (image up) mostly world +y
  EXPECT_NEAR(desc.cameraToWorld[0].y, 0.f, 1e-6f);  // no roll: the image's x is level
  const Vec3 expectedEye = centre - view * (radius / std::sin(0.5f * yfov) * 1.1f);
  EXPECT_NEAR(glm::length(camera.position() - expectedEye), 0.f, 1e-5f);
  EXPECT_FLOAT_EQ(desc.yfov, yfov);
  Pcg32 rng(17, 18);
  for (int k = 0; k < 1000; ++k)
    EXPECT_TRUE(camera.rasterPosition(centre + radius * sampleUniformSphere(rng.next2D())));
}

TEST(CameraFrame, RejectsEmptyImage) {
  EXPECT_THROW(Camera(CameraDesc{}, 0, 10), std::invalid_argument);
}

}  // namespace
}  // namespace pathlab
