// A homogeneous participating medium (the seed's "media": the transmittance T_r on every edge and
// vertices integrated with the volume measure), as glTF describes one: KHR_materials_volume's
// attenuation gives the extinction, the KHR_materials_volume_scatter draft (glTF PR 2453) its split
// into scattering and absorption and the Henyey-Greenstein anisotropy.
#pragma once

#include "core/math/types.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace pathlab {

struct VolumeGrid;  // volume_grid.h

// The PATHLAB_materials_volume_grid extension of a volume material (issue 35, README): a float
// density grid of an OpenVDB file scaling the medium's coefficients point by point,
// sigma_t(x) = density(x) densityScale sigma_t (KHR_materials_volume's), and sigma_s alike.
struct VolumeGridRef {
  std::string uri;                 // the .vdb, relative to the glTF file
  std::string grid = "density";    // the grid's name in it
  float densityScale = 1.f;
  // Set by the loader: the world transform of the node(s) that instance the material's meshes
  // (index space -> grid transform -> node transform -> world), and the grid it read.
  bool placed = false;
  Mat4 nodeToWorld{1.f};
  std::shared_ptr<const VolumeGrid> data;
};

// glTF's parameters of a closed volume (a material with KHR_materials_volume and transmission).
struct VolumeDesc {
  Spectrum attenuationColor{1.f};
  float attenuationDistance = std::numeric_limits<float>::infinity();
  bool scatters = false;              // KHR_materials_volume_scatter present
  Spectrum multiscatterColor{0.f};    // its multiscatterColor (default 0: the draft's)
  float anisotropy = 0.f;             // its scatterAnisotropy, the HG g
  std::optional<VolumeGridRef> grid;  // PATHLAB_materials_volume_grid: heterogeneous
};

struct HomogeneousMedium {
  Spectrum sigmaT{0.f};  // extinction per unit length, per channel
  Spectrum sigmaS{0.f};  // scattering (<= sigmaT); absorption is sigmaT - sigmaS
  float g = 0.f;         // Henyey-Greenstein anisotropy

  // KHR_materials_volume: sigmaT = -ln(attenuationColor) / attenuationDistance per channel (a
  // channel with colour 0 is opaque: a large finite sigmaT). Without the scatter extension the
  // medium only absorbs; with it sigmaS = albedo x sigmaT, the albedo from multiscatterColor
  // (singleScatterAlbedo).
  static HomogeneousMedium fromVolume(const VolumeDesc& v);

  Spectrum transmittance(float distance) const;
  bool scatters() const { return maxComponent(sigmaS) > 0.f; }
  bool isVacuum() const { return !(maxComponent(sigmaT) > 0.f); }
};

// The single-scattering albedo whose multiple-scattering albedo in a semi-infinite slab is
// `multiscatter` for anisotropy g: the mapping the KHR_materials_volume_scatter draft takes from
// OpenPBR (subsurface "scatter colour"): with s^2 = (1 - a) / (1 - g a) the multiscatter albedo is
// (1 - s)(1 - 0.139 s) / (1 + 1.17 s); inverted here per channel by bisection on s (it decreases
// monotonically from 1 at s = 0 to 0 at s = 1). A multiscatter colour of 1 gives albedo 1: a white
// medium absorbs nothing.
Spectrum singleScatterAlbedo(const Spectrum& multiscatter, float g);

// Distance sampling along a segment of length tMax in a scattering medium, with spectral MIS over
// the three channels (pbrt-v3 HomogeneousMedium::Sample; the one-sample model's balance heuristic,
// Veach 1997 sec. 9.2.4): a channel c is chosen uniformly and t ~ sigmaT_c exp(-sigmaT_c t), so the
// density is the channels' average. `weight` is the throughput factor over that density:
// sigmaS T(t) / pdf(t) for a scattering event before tMax, T(tMax) / P(t >= tMax) otherwise.
struct DistanceSample {
  bool scattered = false;
  float t = 0.f;       // where it scattered (scattered only)
  Spectrum weight{1.f};
};
DistanceSample sampleDistance(const HomogeneousMedium& m, float tMax, float uChannel, float u);
// The densities of sampleDistance, for the tests: of scattering at t (per unit length), and of
// passing a segment of length tMax (a probability).
float distancePdf(const HomogeneousMedium& m, float t);
float passProbability(const HomogeneousMedium& m, float tMax);

}  // namespace pathlab
