// The procedural density grids.
#include "core/media/procedural_volumes.h"

#include "core/math/rng.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

namespace {

// Value noise: a random value per integer lattice point (hashed), smoothly interpolated.
float latticeValue(int x, int y, int z, uint64_t seed) {
  const uint64_t h = mixBits(seed ^ mixBits(uint64_t(uint32_t(x)) ^ (uint64_t(uint32_t(y)) << 21) ^ (uint64_t(uint32_t(z)) << 42)));
  return float(h >> 40) * 0x1p-24f;
}

float valueNoise(const Vec3& p, uint64_t seed) {
  const Vec3 f = glm::floor(p);
  const Vec3 w = p - f;
  const Vec3 s = w * w * (3.f - 2.f * w);  // smoothstep
  const int x = int(f.x), y = int(f.y), z = int(f.z);
  auto lerp = [](float a, float b, float t) { return a + t * (b - a); };
  float c[2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      c[dz][dy] = lerp(latticeValue(x, y + dy, z + dz, seed), latticeValue(x + 1, y + dy, z + dz, seed), s.x);
  return lerp(lerp(c[0][0], c[0][1], s.y), lerp(c[1][0], c[1][1], s.y), s.z);
}

float fbm(Vec3 p, uint64_t seed) {
  float sum = 0.f, amplitude = 0.5f;
  for (int octave = 0; octave < 5; ++octave) {
    sum += amplitude * valueNoise(p, seed + uint64_t(octave));
    p *= 2.03f;
    amplitude *= 0.5f;
  }
  return sum;  // about [0, 1)
}

}  // namespace

const char* proceduralVolumeName(ProceduralVolume v) {
  switch (v) {
    case ProceduralVolume::Smoke: return "smoke";
    case ProceduralVolume::Constant: return "constant";
    case ProceduralVolume::Ramp: return "ramp";
  }
  return "?";
}

bool parseProceduralVolume(const std::string& name, ProceduralVolume& out) {
  for (ProceduralVolume v : {ProceduralVolume::Smoke, ProceduralVolume::Constant, ProceduralVolume::Ramp})
    if (name == proceduralVolumeName(v)) {
      out = v;
      return true;
    }
  return false;
}

DensityGrid makeProceduralVolume(ProceduralVolume kind, int n, float value, uint64_t seed) {
  DensityGrid g;
  if (kind != ProceduralVolume::Smoke) {
    // Voxels -1 .. n: the field is exact (not fading) up to the cube's faces at -0.5 and 0.5.
    g.origin = glm::ivec3(-1);
    g.size = glm::ivec3(n + 2);
    g.values.resize(g.voxelCount());
    for (int k = 0; k < g.size.z; ++k) {
      // Voxel index k - 1 lies at z = -0.5 + (k - 0.5) / n.
      const float z = -0.5f + (float(k) - 0.5f) / float(n);
      const float v = kind == ProceduralVolume::Constant ? value : value * (z + 1.f);
      std::fill_n(g.values.begin() + ptrdiff_t(size_t(k) * size_t(g.size.x) * size_t(g.size.y)),
                  size_t(g.size.x) * size_t(g.size.y), v);
    }
    return g;
  }
  g.origin = glm::ivec3(0);
  g.size = glm::ivec3(n);
  g.values.assign(g.voxelCount(), 0.f);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        // Cube coordinates in [0, 1], y up, warped by low-frequency noise so the plume curls.
        const Vec3 c = (Vec3(float(i), float(j), float(k)) + 0.5f) / float(n);
        const Vec3 warp(fbm(c * 3.f, seed + 11), fbm(c * 3.f, seed + 23), fbm(c * 3.f, seed + 37));
        const Vec3 p = c + 0.18f * (warp - 0.5f) * (0.3f + c.y);
        const float height = std::clamp(p.y, 0.f, 1.f);
        // The column's axis sways with height; its radius grows from 0.07 to 0.42.
        const Vec2 axis(0.5f + 0.08f * std::sin(6.f * height), 0.5f + 0.06f * std::cos(4.5f * height));
        const float radius = 0.07f + 0.35f * height;
        const float r = glm::length(Vec2(p.x, p.z) - axis) / radius;
        const float turbulence = fbm(p * 7.f + Vec3(0.f, -3.f * height, 0.f), seed);
        const float edge = 1.f - r + 1.2f * (turbulence - 0.5f);
        if (!(edge > 0.f)) continue;
        // Dense at the bottom, thinning upward, wispy where the noise is low (its square sharpens
        // the contrast); faded near the top and bottom faces so the plume does not end on a cut.
        const float falloff = std::clamp(c.y / 0.06f, 0.f, 1.f) * std::clamp((1.f - c.y) / 0.15f, 0.f, 1.f);
        const float density =
            std::min(1.f, 3.f * edge) * (1.f - 0.55f * height) * std::min(1.f, 4.f * sqr(turbulence)) * falloff;
        g.values[(size_t(k) * size_t(n) + size_t(j)) * size_t(n) + size_t(i)] = std::clamp(density, 0.f, 1.f);
      }
  return g;
}

}  // namespace pathlab
