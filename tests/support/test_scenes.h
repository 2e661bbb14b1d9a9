// Scenes built in code for closed-form tests: exact geometry and materials, no file in between.
#pragma once

#include "core/math/rng.h"
#include "core/scene/scene_desc.h"

#include <functional>

namespace pathlab::test {

// A pure Lambertian glTF material (KHR_materials_specular factor 0) with albedo rho.
Material lambertian(float rho, Spectrum emission = Spectrum(0.f));

// Quad p0 p1 p2 p3 (counter-clockwise seen from the side its normal points to).
TriangleMesh quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, int material);

// Axis-aligned box [-h, h]^3 with faces pointing inward (a closed room seen from inside).
std::vector<TriangleMesh> inwardBox(float h, int material);

CameraDesc lookAt(const Vec3& eye, const Vec3& target, const Vec3& up, float yfov);

// Mean and standard error of a per-sample estimator.
struct MeanEstimate {
  double mean = 0.0, standardError = 0.0;
  uint64_t count = 0;
  double zScore(double expected) const { return (mean - expected) / standardError; }
};

class RunningStats {
 public:
  void add(double v) {
    ++n_;
    const double d = v - mean_;
    mean_ += d / static_cast<double>(n_);
    m2_ += d * (v - mean_);
  }
  MeanEstimate estimate() const {
    return {mean_, n_ > 1 ? std::sqrt(m2_ / static_cast<double>(n_ - 1) / static_cast<double>(n_)) : 0.0, n_};
  }

 private:
  uint64_t n_ = 0;
  double mean_ = 0.0, m2_ = 0.0;
};

}  // namespace pathlab::test
