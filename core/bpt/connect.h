// connect(s, t): the unweighted contribution of bidirectional technique (s, t) for one pair of
// subpaths (Veach 1997, sec. 10.2; pbrt-v4 ConnectBDPT without the MIS weight).
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/bpt/subpath.h"
#include "core/bsdf/bsdf.h"
#include "core/camera/camera.h"
#include "core/media/phase_function.h"
#include "core/math/rng.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"

namespace pathlab {

// The solid-angle densities the connection's BSDF evaluations produce at its two surface
// endpoints qs = x(s-1) (light side) and pt (camera side), in both directions. misWeight needs
// exactly these four (pbrt-v4 recomputes them; SmallVCM carries them): passing them on saves
// rebuilding both BSDFs per connection.
struct ConnectionPdfs {
  bool atLight = false;    // qs is a surface vertex connect() evaluated
  float qsToPt = 0.f;      // density at qs of the direction toward pt, arriving from x(s-2)
  float qsToPrev = 0.f;    // density at qs of the direction toward x(s-2), arriving from pt
  bool atCamera = false;   // pt is a surface vertex connect() evaluated
  float ptToQs = 0.f;      // density at pt of the direction toward qs, arriving from its predecessor
  float ptToPrev = 0.f;    // density at pt of the direction toward its predecessor, arriving from qs
  bool atLens = false;     // t = 1: pt is the lens point connect() sampled
  float lensToQs = 0.f;    // the camera's directional density (pdfWe) toward qs from that lens point
};

// The visibility test a connection still needs: between two surface (or light, lens) points, or
// from a point toward a directional light.
struct ShadowRay {
  Vec3 a{0.f}, na{0.f}, ea{0.f};  // first endpoint, its geometric normal and error bound
  Vec3 b{0.f}, nb{0.f}, eb{0.f};  // second endpoint (unused toward infinity)
  Vec3 direction{0.f};            // toward the directional light, when toInfinity
  bool toInfinity = false;
  int medium = -1;                // scenes with media: the medium it leaves a in (set by formConnection)

  // Set in place, field by field: assigning a braced temporary made the compiler build it on the
  // stack and copy it in wider pieces than it was written in, a store-forwarding stall per field
  // on every connection.
  void between(const Vec3& pa, const Vec3& nA, const Vec3& eA, const Vec3& pb, const Vec3& nB, const Vec3& eB) {
    a = pa, na = nA, ea = eA, b = pb, nb = nB, eb = eB;
    toInfinity = false;
  }
  void toward(const Vec3& pa, const Vec3& nA, const Vec3& eA, const Vec3& dir) {
    a = pa, na = nA, ea = eA, direction = dir;
    toInfinity = true;
  }
};
// True when nothing lies between the endpoints (one Embree occlusion query).
bool unoccluded(const Scene& scene, const ShadowRay& ray);
// Scenes with media: the transmittance between the endpoints through the media and index-matched
// boundaries on the way, zero when a surface blocks it (Scene::transmittance).
Spectrum transmittance(const Scene& scene, const ShadowRay& ray);

struct Connection {
  Spectrum L{0.f};     // unweighted contribution if the shadow ray is unoccluded
  Vec2 pRaster{0.f};   // t = 1: where it lands on the film (splat); otherwise unused
  // s = 1 and t = 1 draw a fresh endpoint (a light sample, a lens point). The estimator divides
  // by its density, so misWeight must see this vertex, not the subpath's own x0 (`hasSampled`).
  PathVertex sampled;
  bool hasSampled = false;
  ConnectionPdfs pdfs;
  ShadowRay shadowRay;  // valid when formConnection returned true
  // s >= 1: edgeLength2 (path_vertex.h) of the connection edge, x(s-1) to x(s), the same bits;
  // what --min-connection compares (mis.h UsableTechniques). Unset for s = 0 (no such edge).
  float edgeLength2 = 0.f;
};

// Technique (s, t) on one pair of prefixes up to the visibility test: lightPath has at least s
// vertices, cameraPath at least t (t >= 1, s >= 0). Returns false when the technique cannot form
// the path (a delta vertex at the connection, f = 0, off the film, ...). Otherwise c holds the
// contribution the path makes if c.shadowRay is unoccluded (s = 0, the camera subpath's own hit
// of an emitter, needs none: needsShadowRay). Only the fields the technique produces are written:
// `c` is scratch reused across techniques, never zero-filled as a whole.
// Rng: Pcg32, or a primary-sample stream (Metropolis); both instances are compiled in connect.cpp.
template <class Rng>
bool formConnection(const Scene& scene, const Camera& camera, const Subpath& lightPath, int s, const Subpath& cameraPath,
                    int t, Rng& rng, Connection& c);
inline bool needsShadowRay(int s) { return s >= 1; }

// The scattering at a medium vertex toward wi, as a connection uses a BSDF evaluation: the phase
// function is value and density in both directions (it is symmetric), and there is no cosine.
inline BsdfEval phaseEval(const Scene& scene, const PathVertex& v, const Vec3& wi) {
  const float p = phaseHG(v.wo, wi, scene.medium(v.media.inside).g);
  return BsdfEval{Spectrum(p), p, p};
}

// formConnection's techniques s >= 2, t >= 2 (path reuse's interior connections, about half of a
// Cornell-box sample's): both ends are surface or medium vertices the walks found, joined by a
// deterministic edge. Inline so that formConnection and the tracer's kernel
// (BidirTracer::evaluate) run this one piece of arithmetic. Writes c.L, c.pdfs, c.shadowRay
// and c.edgeLength2 (not c.hasSampled: no endpoint is drawn afresh).
[[gnu::always_inline]] inline bool formInteriorConnection(const Scene& scene, const Subpath& lightPath, int s,
                                                          const Subpath& cameraPath, int t, Connection& c) {
  const PathVertex& pt = cameraPath[t - 1];
  const bool ptMedium = pt.type == VertexType::Medium;
  if (pt.isDelta || (pt.type != VertexType::Surface && !ptMedium)) return false;
  const PathVertex& qs = lightPath[s - 1];
  const bool qsMedium = qs.type == VertexType::Medium;
  if (qs.isDelta || (qs.type != VertexType::Surface && !qsMedium)) return false;
  Vec3 d = qs.p - pt.p;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.f)) return false;
  d /= std::sqrt(dist2);
  const BsdfEval fq = qsMedium ? phaseEval(scene, qs, -d) : lightPath.bsdf(s - 1).eval(qs.wo, -d, TransportMode::Importance);
  if (isBlack(fq.f)) return false;
  const BsdfEval fp = ptMedium ? phaseEval(scene, pt, d) : cameraPath.bsdf(t - 1).eval(pt.wo, d, TransportMode::Radiance);
  if (isBlack(fp.f)) return false;
  c.pdfs = ConnectionPdfs{true, fq.pdfFwdW, fq.pdfRevW, true, fp.pdfFwdW, fp.pdfRevW};
  // Geometry term with shading normals (pbrt-v4 G), matching the walks' |cos| with ns; a medium
  // vertex has no cosine (volume measure).
  const float G = (qsMedium ? 1.f : absDot(qs.ns, d)) * (ptMedium ? 1.f : absDot(pt.ns, d)) / dist2;
  c.L = qs.beta * fq.f * fp.f * pt.beta * G;
  if (isBlack(c.L)) return false;
  c.shadowRay.between(pt.p, pt.ng, pt.pError, qs.p, qs.ng, qs.pError);
  c.shadowRay.medium = mediumToward(pt, d);
  c.edgeLength2 = dist2;  // (qs - pt)^2, the same bits as edgeLength2(qs, pt)
  return true;
}

// formConnection and the shadow ray: the unweighted contribution of (s, t), zero when it cannot
// form the path or the shadow ray is occluded. For tests; the tracer traces the shadow ray only
// when the MIS weight asks for the contribution.
Connection connect(const Scene& scene, const Camera& camera, const Subpath& lightPath, int s,
                   const Subpath& cameraPath, int t, Pcg32& rng, Counters& counters);

// The light vertex of a fresh light sample ls of light li (next-event estimation's, s = 1; the
// equiangular technique's): its densities as a light subpath's origin chosen by power (pdfFwdA,
// pmfPower) and as next-event estimation's choice for the vertex it connects to (pdfNeeA,
// pmfNee), its throughput Li / (pmfChosen pdfW) with the pmf the light was in fact chosen with.
void setLightSampleVertex(const Scene& scene, int li, const LightLiSample& ls, float pmfNee, float pmfPower,
                          float pmfChosen, PathVertex& v);

// Emission of light-subpath vertex x0 toward direction `w`, divided by the density with which x0
// was chosen (light pmf x position pdf): Le / (pmf pdfPosA) or I / pmf; zero for a direction a
// directional light does not emit in.
Spectrum emittedOverOriginPdf(const Scene& scene, const PathVertex& x0, const Vec3& w);

}  // namespace pathlab
