// Density grids pathlab makes itself (`pathlab make-volume`, the tests): the bundled smoke
// scene's plume, a constant block and a linear ramp, each a DensityGrid of n^3 voxels whose voxel
// centres fill the unit cube [-0.5, 0.5]^3 (voxel size 1 / n, first centre at -0.5 + 0.5 / n).
#pragma once

#include "core/media/density_grid.h"

#include <cstdint>
#include <string>
#include <vector>

namespace pathlab {

enum class ProceduralVolume { Smoke, Constant, Ramp };

// "smoke", "constant", "ramp"; and the inverse (false for an unknown name).
const char* proceduralVolumeName(ProceduralVolume v);
bool parseProceduralVolume(const std::string& name, ProceduralVolume& out);

// smoke: a rising plume, a column that widens and thins with height, its edge broken by
// octaves of value noise (deterministic in `seed`); densities in [0, 1].
// constant: `value` everywhere in the cube (padding: one more voxel each side than the cube
//   needs, so that the trilinear field is exactly `value` up to the cube's faces).
// ramp: value x (z + 1), linear in z across the cube (padded the same way; positive throughout).
DensityGrid makeProceduralVolume(ProceduralVolume kind, int n, float value = 1.f, uint64_t seed = 1);

// The voxel size and world position of index (0, 0, 0) for a grid of makeProceduralVolume(.., n).
inline float proceduralVoxelSize(int n) { return 1.f / float(n); }
inline Vec3 proceduralOrigin(int n) { return Vec3(-0.5f + 0.5f / float(n)); }

}  // namespace pathlab
