// Scenes built in code for closed-form tests: exact geometry and materials, no file in between.
#pragma once

#include "core/math/rng.h"
#include "core/scene/scene_desc.h"
#include "tests/support/statistics.h"

#include <functional>

namespace pathlab::test {

// A pure Lambertian glTF material (KHR_materials_specular factor 0) with albedo rho.
Material lambertian(float rho, Spectrum emission = Spectrum(0.f));

// Quad p0 p1 p2 p3 (counter-clockwise seen from the side its normal points to).
TriangleMesh quad(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, int material);

// Axis-aligned box [-h, h]^3 with faces pointing inward (a closed room seen from inside).
std::vector<TriangleMesh> inwardBox(float h, int material);

// The white furnace: an inward box [-1,1]^3, every wall Lambertian with albedo rho emitting Le,
// and a camera inside it.
SceneDesc furnace(float rho, float Le);

// A 100 m x 100 m Lambertian floor at y = 0 facing +y (no light, no camera).
SceneDesc floorScene(float rho);

CameraDesc lookAt(const Vec3& eye, const Vec3& target, const Vec3& up, float yfov);

}  // namespace pathlab::test
