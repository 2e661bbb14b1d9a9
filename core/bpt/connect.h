// connect(s, t): the unweighted contribution of bidirectional technique (s, t) for one pair of
// subpaths (Veach 1997, sec. 10.2; pbrt-v4 ConnectBDPT without the MIS weight).
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/bpt/subpath.h"
#include "core/camera/camera.h"
#include "core/math/rng.h"
#include "core/metrics/counters.h"
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
};

struct Connection {
  Spectrum L{0.f};     // unweighted contribution; zero when the technique cannot form the path
  Vec2 pRaster{0.f};   // t = 1: where it lands on the film (splat); otherwise unused
  // s = 1 and t = 1 draw a fresh endpoint (a light sample, a lens point). The estimator divides
  // by its density, so misWeight must see this vertex, not the subpath's own x0 (`hasSampled`).
  PathVertex sampled;
  bool hasSampled = false;
  bool blocked = false;  // a non-zero contribution whose shadow ray was occluded
  ConnectionPdfs pdfs;
};

// lightPath has at least s vertices, cameraPath at least t (t >= 1, s >= 0). Vertices flagged
// isDelta cannot be connected: the contribution is then zero.
Connection connect(const Scene& scene, const Camera& camera, const Subpath& lightPath, int s,
                   const Subpath& cameraPath, int t, Pcg32& rng, Counters& counters);

// Emission of light-subpath vertex x0 toward direction `w`, divided by the density with which x0
// was chosen (light pmf x position pdf): Le / (pmf pdfPosA) or I / pmf; zero for a direction a
// directional light does not emit in.
Spectrum emittedOverOriginPdf(const Scene& scene, const PathVertex& x0, const Vec3& w);

}  // namespace pathlab
