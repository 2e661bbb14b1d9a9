// The bidirectional equiangular technique family E(1, k) (issue 35): Kulla and Fajardo's
// equiangular sampling (2012; core/media/equiangular.h) made a technique of the path integral
// framework, beside the connections C(s, t) and weighted with them by MIS.
//
// For a path x0 x1 x2 ... x_k (x0 on a light, x_k the camera) whose x1 lies in a homogeneous
// scattering medium, E(1, k) samples x_k .. x2 as the camera subpath does, the ray x2 shoots as
// the walk does, a light and a point x0 on it chosen from x2 (next-event estimation's light choice
// with x2 as the receiver), then x1 on that ray with the equiangular density toward x0, and joins
// x1 to x0. C(1, k) samples the same path with distance sampling in place of the equiangular step
// and x1 as the light choice's receiver, so in the area (volume) measure
//     p_E(x) / p_C(1,k)(x) = [pmfNee(x0 | x2) / pmfNee(x0 | x1)] p_e(x1) / p_d(x1),
// p_e and p_d both densities per unit length along the ray from x2 (their conversion to the volume
// measure, the same 1/|x1 - x2|^2 times the direction's density at x2, cancels).
//
// Two choices keep every weight a function of the path alone, hence unbiased:
//  - p_e is the density on the unbounded ray (theta_b = pi/2): evaluating it for a path another
//    technique sampled then needs no ray cast. A sample past the surface the ray meets first
//    contributes only if the medium continues there (an index-matched boundary), else nothing.
//  - p_d is distance sampling's closed form in x1's medium, sigma_t T over the distance (the
//    walks' own densities leave their distance probabilities out, subpath.cpp). E is defined
//    only where x1's medium is homogeneous, and where the ray leaves x2 in that same medium.
#pragma once

#include "core/bpt/bidir_options.h"
#include "core/bpt/connect.h"
#include "core/bpt/path_vertex.h"
#include "core/bpt/subpath.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"

namespace pathlab {

// Whether E can sample anything in this scene: some homogeneous medium scatters.
bool hasEquiangularMedium(const Scene& scene);
// Whether the bidirectional tracer samples the family with these options: --medium-sampling not
// distance, path reuse, no merge enabled or isolated, and a medium E can sample. Elsewhere no
// weight counts it, no table keeps it (core/render/render_settings.h pyramidFamilies).
bool equiangularFamilySampled(const Scene& scene, const BidirOptions& options);

// The factor [pmfNee(x0 | x2) / pmf(x0)] p_e(x1) / p_d(x1) of the path x0 x1 x2 ... (pmf: the
// light subpaths' choice by power); 0 where E cannot sample the path (x1 not in a homogeneous
// scattering medium, the ray from x2 toward x1 not starting in it, x0 at infinity or on x1's ray
// line). pathDensities turns it into p_E / p_C(2,k) (PathDensities::equiangular).
double equiangularFactor(const Scene& scene, const PathVertex& x0, const PathVertex& x1, const PathVertex& x2);

// Technique E(1, t) on the camera subpath's first t - 1 vertices and the ray z(t-2) shot
// (cameraPath.rays[t - 2]): places x (the camera vertex z(t-1) it puts in place of the walk's),
// chooses the light point, and forms the connection x -> light as formConnection's s = 1 does,
// into `c` (c.sampled the light vertex, c.pdfs at x, c.shadowRay to the light, c.L unweighted,
// without the shadow ray's transmittance). Counts the ray it may cast (a sample past the ray's
// first surface). Returns false when it forms no path.
bool formEquiangularConnection(const Scene& scene, const Subpath& cameraPath, int t, Pcg32& rng, PathVertex& x,
                               Connection& c, Counters& counters);

}  // namespace pathlab
