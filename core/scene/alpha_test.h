// Alpha coverage as Embree filter callbacks: MASK cut-outs and BLEND's stochastic transparency,
// seen by every ray the renderer traces (camera and light walks, shadow rays, connections).
#pragma once

#include "core/scene/material.h"
#include "core/scene/scene_desc.h"

#include <embree3/rtcore.h>

namespace pathlab {

// What the callbacks read at a candidate hit: the triangle's uvs and colours, its material and
// the textures. Must outlive the Embree scene (Scene keeps these beside it).
struct AlphaGeometry {
  const TriangleMesh* mesh = nullptr;
  const Material* material = nullptr;
  const std::vector<Texture>* textures = nullptr;
};

// Whether the ray meets the surface at barycentrics (b1, b2) of triangle `prim`:
//  - MASK: alpha >= alphaCutoff (glTF 2.0 sec. 3.9.4), the same answer for every ray;
//  - BLEND: with probability alpha, decided by `u` in [0, 1). Averaged over u this is the
//    surface's coverage alpha, so a path through k such layers is carried with the product of
//    their (1 - alpha): unbiased for the blended surface, in every technique, whatever the MIS
//    weights (they depend only on the path's vertices and still sum to one).
bool alphaCovers(const AlphaGeometry& g, uint32_t prim, float b1, float b2, float u);

// Attaches the intersect and occluded filters to `geometry` (before rtcCommitGeometry); only
// geometries whose material has an alpha mode get them, so opaque scenes pay nothing.
void attachAlphaFilter(RTCGeometry geometry, const AlphaGeometry* g);

}  // namespace pathlab
