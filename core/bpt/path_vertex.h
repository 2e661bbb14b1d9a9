// One vertex of a light or camera subpath (Veach 1997, ch. 10; pbrt-v4 BDPT `Vertex`): plain,
// trivially copyable data with both of its densities in area measure, set when it is created.
#pragma once

#include "core/lights/light_bounds.h"
#include "core/math/types.h"
#include "core/math/medium_interface.h"

#include <limits>
#include <type_traits>

namespace pathlab {

// Medium: a scattering point inside a participating medium (issue 16), integrated with the volume
// measure: no normal, no cosine in its densities, the phase function as its BSDF.
enum class VertexType : uint8_t { Camera, Light, Surface, Medium };

struct PathVertex {
  VertexType type = VertexType::Surface;
  Vec3 p{0.f};
  Vec3 ng{0.f};          // geometric normal (area light: its triangle normal; punctual, camera: 0)
  Vec3 ns{0.f};          // shading normal (surfaces only)
  Vec3 wo{0.f};          // unit direction toward the previous vertex of its own subpath (0 at x0)
  Vec3 pError{0.f};      // floating-point error bound of p (ray.h interpolationError); 0 off surfaces
  Vec2 uv{0.f};          // TEXCOORD_0 (light vertices: in the light's emission uv set)
  Vec2 uv1{0.f};         // TEXCOORD_1 (surfaces)
  Spectrum color{1.f};   // COLOR_0 (surfaces)
  int material = -1;     // surfaces
  // Scenes with media: the media either side of a surface (as ng orients them), the medium a
  // medium vertex, camera or punctual light lies in (both sides the same). mediumToward().
  MediumInterface media;
  int light = -1;        // light vertices, and surfaces lying on an area light (index in LightSet)
  Spectrum beta{0.f};    // throughput of the subpath up to and including this vertex
  // Density of this vertex when sampled from its own subpath's side (pdfFwdA) and from the other
  // side (pdfRevA), both in area measure (pbrt-v4 `pdfFwd` / `pdfRev`). A delta density counts
  // as one (pbrt's "remap zero to one"), applied where the ratios are formed.
  float pdfFwdA = 0.f;
  float pdfRevA = 0.f;
  // x0 of a light subpath with an x1, and the light sample of next-event estimation: its density
  // when next-event estimation chooses it for x1 (LightSet::pmfNee, which may depend on x1) in
  // place of the power-proportional choice in pdfFwdA. Technique (1, t >= 2) samples x0 so, the
  // others as a light subpath's origin (mis.h, PathDensities::x0Nee). Equal to pdfFwdA when the
  // scene chooses by power alone.
  float pdfNeeA = 0.f;
  // convertDensity(1, this, predecessor): a solid-angle density at this vertex toward the vertex
  // before it on its own subpath, times this, is an area density there. Set by the walks; the
  // O(1) MIS weight uses it for the predecessor of each connection end (mis.cpp).
  float areaToPrev = 0.f;
  // What the MIS densities leave out of the walk's decisions before this vertex, relative to a
  // function of the path alone (optimal_mis.h): Russian roulette's 1 / q (RussianRoulette::weight),
  // and at each delta vertex of a light walk the camera side's probability of choosing the same lobe
  // over the light side's (a delta vertex's densities count one; one where the lobe is chosen alike
  // from both sides). Optimal MIS scales its correction by it. 1 for fresh endpoints.
  float omittedFactor = 1.f;
  bool isDelta = false;          // a delta BSDF lobe was sampled here: cannot be connected
  bool isDeltaPosition = false;  // point / spot light, pinhole: cannot be hit by a ray
  // Directional or environment light, at infinity: the density of the next vertex from it is
  // planar (the emission disk's), and a density toward it stays in solid angle (pbrt-v4
  // ConvertDensity). ng is then the direction light travels, p a far point along -ng.
  bool isInfinite = false;
  bool isDeltaDirection = false;  // directional light: an escaping camera ray never meets it

  bool onSurface() const { return type == VertexType::Surface || (type == VertexType::Light && ng != Vec3(0.f) && !isInfinite); }
};

static_assert(std::is_trivially_copyable_v<PathVertex>);

// Where v receives light in next-event estimation: its point, with its normal on a surface.
inline LightSampleContext neeContext(const PathVertex& v) {
  return LightSampleContext{v.p, v.type == VertexType::Medium ? Vec3(0.f) : v.ng};
}

// The medium a segment leaving v in direction w travels through (-1: none).
inline int mediumToward(const PathVertex& v, const Vec3& w) { return v.media.toward(v.ng, w); }

// Solid-angle density at `from` of the direction toward `to` -> area density at `to`
// (pbrt-v4 Vertex::ConvertDensity): |cos| at the receiving vertex over distance squared; no
// cosine when the receiver is a camera or punctual light. From a light at infinity (`from`
// infinite) the given value is already an area density on a plane normal to the light, so only
// the receiver's cosine applies; toward one (`to` infinite) a direction is all there is to sample,
// and the density stays in solid angle.
[[gnu::always_inline]] inline float convertDensity(float pdfW, const PathVertex& from, const PathVertex& to) {
  const Vec3 d = to.p - from.p;
  const float dist2 = glm::dot(d, d);
  if (from.isInfinite) return to.onSurface() ? pdfW * absDot(to.ng, glm::normalize(from.ng)) : pdfW;
  if (to.isInfinite) return pdfW;
  if (!(dist2 > 0.f)) return 0.f;
  float pdf = pdfW / dist2;
  if (to.onSurface()) pdf *= absDot(to.ng, d) / std::sqrt(dist2);
  return pdf;
}

// |b - a|^2, the squared length of an edge; infinite toward a light at infinity.
inline float edgeLength2(const PathVertex& a, const PathVertex& b) {
  if (a.isInfinite || b.isInfinite) return std::numeric_limits<float>::infinity();
  const Vec3 e = b.p - a.p;
  return glm::dot(e, e);
}

}  // namespace pathlab
