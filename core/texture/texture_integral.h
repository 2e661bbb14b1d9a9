// The mean of a filtered texture over a triangle of its uv space: what an emissive triangle's
// power integrates (AreaLight), computed once at load.
#pragma once

#include "core/texture/texture.h"

namespace pathlab {

// Mean of Texture::sample over the uv triangle (uv0, uv1, uv2), uniform in area (which is uniform
// in area on any triangle mapped to it affinely, e.g. the mesh triangle carrying these uvs).
// Exact up to rounding: the filtered texture is one polynomial of degree <= 2 on each cell of a
// grid (bilinear: between four texel centres; nearest: one texel), so the triangle is clipped
// against every cell it covers and the polynomial integrated over the piece in closed form, in
// O(cells covered + rows covered), wrap modes applied per texel index. A triangle without area in
// uv space (collinear uvs) or with a footprint far larger than the texture is averaged by a
// stratified quadrature of sample() instead.
Vec4 meanOverTriangle(const Texture& texture, Vec2 uv0, Vec2 uv1, Vec2 uv2);

}  // namespace pathlab
