// Camera and light subpaths: random walks that store their vertices with both area densities
// (Veach 1997, sec. 10.2; pbrt-v4 BDPT GenerateCameraSubpath / GenerateLightSubpath / RandomWalk).
#pragma once

#include "core/bpt/path_vertex.h"
#include "core/bsdf/bsdf.h"
#include "core/camera/camera.h"
#include "core/math/rng.h"
#include "core/sampling/primary_samples.h"
#include "core/counters/counters.h"
#include "core/scene/scene.h"

#include <vector>

namespace pathlab {

// The ray a camera walk shot from vertex i, as it left it (WalkOptions::recordRays): what the
// equiangular technique E(1, i + 2) needs to place its vertex on that ray instead of where
// distance sampling put z(i+1) (core/bpt/equiangular_technique.h). Recorded before the step, so
// also when the step ended the walk (an escape, an absorption): the technique's density then does
// not depend on what distance sampling did on the ray.
struct WalkRay {
  Vec3 d{0.f};          // unit direction
  Spectrum beta{0.f};   // the walk's throughput entering the ray (after the scattering at i and Russian roulette)
  float pdfFwdW = 0.f;  // the density with which d was chosen (0 after a delta lobe, as pdfFwdA)
  float firstSegment = 0.f;  // the distance to the first surface it meets (index-matched or not; MediaStep)
  int medium = -1;      // the medium it starts in
};

// A subpath in a buffer whose capacity is set once (per thread), so that generating a sample
// never allocates. Vertex 0 is the camera (CameraSubpath) or the point on the light (LightSubpath).
// The BSDF of every surface vertex is kept beside it (a medium vertex's phase function is its
// medium's, looked up): the connections and the walk evaluate it
// again, and building it (material and texture lookups, frame) is a large part of a sample's cost.
struct Subpath {
  std::vector<PathVertex> vertices;
  std::vector<Bsdf> bsdfs;  // bsdfs[i] is valid when vertices[i] is a surface vertex
  int count = 0;
  // Camera walks with WalkOptions::recordRays: rays[i] is the ray that left vertex i, i < rayCount.
  std::vector<WalkRay> rays;
  int rayCount = 0;

  void setCapacity(int n) {
    if (static_cast<int>(vertices.size()) < n) {
      vertices.resize(static_cast<size_t>(n));
      bsdfs.resize(static_cast<size_t>(n));
    }
  }
  const PathVertex& operator[](int i) const { return vertices[static_cast<size_t>(i)]; }
  PathVertex& operator[](int i) { return vertices[static_cast<size_t>(i)]; }
  const PathVertex* data() const { return vertices.data(); }
  const Bsdf& bsdf(int i) const { return bsdfs[static_cast<size_t>(i)]; }
};
struct CameraSubpath : Subpath {};
struct LightSubpath : Subpath {};

struct WalkOptions {
  int maxVertices = 0;         // camera subpath: maxLength + 1; light subpath: maxLength
  bool russianRoulette = true;  // the path tracer's policy (russian_roulette.h), on the walk's own throughput
  int cameraMedium = -1;        // camera walks: the medium the camera is in (Scene::mediumAt)
  bool recordRays = false;      // camera walks: fill Subpath::rays (the equiangular technique)
};

// The camera subpath through film position pRaster (pixels). Returns the number of vertices.
// Rng (here and below): Pcg32, or a stream of a primary sample vector (Metropolis,
// core/sampling/primary_samples.h); both instances are compiled in subpath.cpp.
template <class Rng>
int generateCameraSubpath(const Scene& scene, const Camera& camera, Vec2 pRaster, Vec2 uLens, Rng& rng,
                          const WalkOptions& options, CameraSubpath& path, Counters& counters);

// The light subpath from a light chosen in proportion to its power. Returns the number of vertices.
template <class Rng>
int generateLightSubpath(const Scene& scene, Rng& rng, const WalkOptions& options, LightSubpath& path,
                         Counters& counters);

}  // namespace pathlab
