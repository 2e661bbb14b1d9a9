// In-code scenes for the bidirectional agreement tests: one with delta components (a smooth
// mirror, a smooth glass sphere, a point light, the pinhole camera) and one without delta
// components or concave corners.
#pragma once

#include "core/scene/scene_desc.h"

namespace pathlab::test {

// Metallic 1, roughness 0 (GGX alpha 0 < kDeltaAlpha): a delta reflection, Fresnel F0 = reflectance.
Material mirror(float reflectance);
// Transmission 1, roughness 0, index ior: delta reflection and delta refraction.
Material glass(float ior = 1.5f);

// A UV sphere with smooth (interpolated) normals, triangles facing outward.
TriangleMesh uvSphere(const Vec3& centre, float radius, int material, int segments = 32, int rings = 16);

enum class DeltaLight { Area, Point };

// A Lambertian floor and back wall (albedo 0.5; the wall's lower edge 0.2 m from the floor's
// far edge), a vertical mirror on the left and a glass sphere, both floating 0.1 m above the
// floor, lit from above by a 1 m square area light (Le = 1.5) or a point light (3 W/sr) at the
// same place, neither of which the camera sees directly. The camera is a pinhole and sees the
// floor, the wall, the mirror and the sphere. No two non-delta surfaces meet at a concave edge
// (a wall standing on the floor would), so every connection's geometry term is bounded and the
// uniform heuristic, which gives the connections (s, t >= 2) a weight of 1/k whatever their
// density, has a finite variance (see integratingSphere). The area light is large so that the
// path tracer, which can sample the light the mirror and the sphere redirect only by hitting the
// light through them, finds those paths often enough for a short render's standard error to be
// trustworthy (with a 0.6 m light it missed them in 1 seed of 5: z = 4.5).
SceneDesc deltaScene(DeltaLight light);

// An integrating sphere: the inside of a Lambertian sphere (radius 2, albedo 0.7) whose top cap
// (the rings within 0.45 rad of the pole) emits Le = 2, around a floating Lambertian sphere
// (radius 0.5, albedo (0.7, 0.4, 0.3)); the camera inside sees both and the cap. No delta
// component, and no concave edge: between two points of a sphere cos cos / d^2 = 1 / (4 R^2),
// so every connection's geometry term is bounded (up to the facets' small dihedral angles) and
// every unweighted technique has a finite variance. In a room the 1 / d^2 of connections near a
// concave edge gives the unweighted techniques with s, t >= 2 infinite variance (the motivation
// of Veach 1997, sec. 10.3 for weighting them), and a z-test needs a finite one. Closed, so long
// paths carry much light.
SceneDesc integratingSphere();

}  // namespace pathlab::test
