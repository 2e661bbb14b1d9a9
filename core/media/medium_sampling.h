// How the path tracer places the scattering vertex whose next-event estimation reaches a light
// (issue 35): by distance sampling along the transmittance (medium.h), by equiangular sampling
// toward the chosen light point (equiangular.h, Kulla and Fajardo 2012), or by both combined with
// MIS (the power heuristic over the two, and over phase sampling where that can hit the light).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace pathlab {

enum class MediumSampling : uint8_t {
  Distance,     // distance sampling alone, as before issue 35
  Equiangular,  // equiangular wherever it can place the vertex; distance sampling elsewhere
  Mis,          // both, weighted by MIS
};

const char* mediumSamplingName(MediumSampling m);
std::optional<MediumSampling> parseMediumSampling(std::string_view name);

}  // namespace pathlab
