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

// Smooth glass of index `ior` (transmission 1), no volume: every lobe a delta.
Material smoothGlass(float ior);

// An index-matched boundary (transmission 1, ior 1, smooth) around a homogeneous medium of
// extinction sigmaT per unit length (attenuationDistance 1); scattering with single-scattering
// albedo 1 and anisotropy g when `scatters` (multiscatterColor 1), else purely absorbing.
Material mediumBoundary(Spectrum sigmaT, bool scatters, float g = 0.f);

// Axis-aligned box [lo, hi] with faces pointing outward (a closed volume seen from outside).
std::vector<TriangleMesh> outwardBox(const Vec3& lo, const Vec3& hi, int material);

// The furnace filled with a scattering, non-absorbing medium (sigmaT, g) bounded by an
// index-matched box just inside the walls: still Le / (1 - rho) everywhere for long paths.
SceneDesc foggyFurnace(float rho, float Le, float sigmaT, float g);

// The furnace holding a smooth glass cube (ior 1.6) and a mirror cube (metal, reflectance 1):
// lossless and not emitting, they leave the field Le / (1 - rho) everywhere for long paths
// (inside the glass Le / (1 - rho) eta^2), so every path through them is a delta chain whose
// expectation is known.
SceneDesc deltaFurnace(float rho, float Le);

// A 100 m x 100 m Lambertian floor at y = 0 facing +y (no light, no camera).
SceneDesc floorScene(float rho);

CameraDesc lookAt(const Vec3& eye, const Vec3& target, const Vec3& up, float yfov);

}  // namespace pathlab::test
