// sampleableWithMerges on hand-made paths: which connections and merges of a path's length could
// sample it (the technique maps' "cannot sample" with vertex merging), against closed-form
// reasoning about delta vertices (Veach 1997, sec. 10.3.5; a merge needs a non-delta surface
// vertex to merge at, Georgiev et al. 2012, sec. 4).
#include "core/bpt/merge_sampleable.h"

#include "core/bpt/merge_mis.h"
#include "core/bpt/subpath.h"
#include "core/sampling/technique_label.h"
#include "core/counters/counters.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace pathlab {
namespace {

PathVertex sampleableVertex(VertexType type, bool delta, int light = -1) {
  PathVertex v;
  v.type = type;
  v.isDelta = delta;
  v.light = light;
  return v;
}

// Bit of technique x in a mask over its length (Technique::slot()).
uint64_t bitOf(Technique x) { return uint64_t{1} << x.slot(); }

// x0 on an area light, x1 and x2 diffuse, x3 a mirror, x4 the pinhole camera (length 4), formed by
// the connection (2,3): (0,5), (1,4) and (2,3) can sample it, (3,2) and (4,1) cannot (x3 is
// delta); the merges at x1 and x2, M(2,4) and M(3,3), can, the one at the mirror, M(4,2), cannot.
TEST(MergeSampleable, ConnectionPathGetsTheMergesAtItsDiffuseVertices) {
  std::vector<PathVertex> light = {sampleableVertex(VertexType::Light, false, 0),
                                   sampleableVertex(VertexType::Surface, false)};
  std::vector<PathVertex> camera = {sampleableVertex(VertexType::Camera, false),
                                    sampleableVertex(VertexType::Surface, true),
                                    sampleableVertex(VertexType::Surface, false)};
  camera[0].isDeltaPosition = true;
  const MisPath path{light.data(), 2, camera.data(), 3, nullptr, nullptr};
  const uint64_t expected = bitOf({0, 5}) | bitOf({1, 4}) | bitOf({2, 3}) | bitOf(Technique::merge(2, 4)) |
                            bitOf(Technique::merge(3, 3));
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Connection), expected);
  // The connections' bits are sampleableTechniques' (which BPT alone uses).
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Connection) & 0x1f, sampleableTechniques(path));
  // Progressive photon mapping merges only at the camera subpath's first non-delta vertex: x2,
  // seen in the mirror x3. M(2,4) at x1 is no technique of ppm's.
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Connection, MergeSite::FirstNonSpecular),
            expected & ~bitOf(Technique::merge(2, 4)));
}

// x0 a point light, x1 a mirror, x2 diffuse, x3 a mirror, x4 the camera, formed by the merge
// M(3,3) at x2 (its MisPath is that of C(3,2): x3 = z1 follows the merged vertex). Every edge has
// a delta end and s = 0 cannot hit a point: no connection can sample the path, only M(3,3). The
// edge x2 -- x3 was sampled by the camera walk, not connected: x3 stays delta.
TEST(MergeSampleable, OnlyTheMergeSamplesLightBetweenMirrors) {
  std::vector<PathVertex> light = {sampleableVertex(VertexType::Light, false, 0),
                                   sampleableVertex(VertexType::Surface, true),
                                   sampleableVertex(VertexType::Surface, false)};
  light[0].isDeltaPosition = true;
  std::vector<PathVertex> camera = {sampleableVertex(VertexType::Camera, false),
                                    sampleableVertex(VertexType::Surface, true)};
  camera[0].isDeltaPosition = true;
  const MisPath path{light.data(), 3, camera.data(), 2, nullptr, nullptr};
  EXPECT_EQ(sampleableWithMerges(path, TechniqueKind::Merge), bitOf(Technique::merge(3, 3)));
}

// A merge is weighed on its merged path (merge_mis.h mergedPathDensities), where every vertex keeps
// its walk's delta flag but the merged one: where z(t-2) is a mirror or glass the connections
// through it and the merge at it cannot sample the path and get no weight, so the weights of the
// techniques that can sample it (sampleableWithMerges) sum to one on every merge path, and
// mergeWeight is the merge's own among them. Reading the merge's path as C(s, t - 1)'s, whose
// patch marks z(t-2) non-delta, failed on about 9 % of these paths with sums down to 0.01.
TEST(MergeSampleable, MergeWeightsOverTheSampleableTechniquesSumToOne) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  const Camera camera(scene.cameraDesc(), 64, 64);
  Counters counters;
  CameraSubpath cameraPath;
  LightSubpath lightPath;
  cameraPath.setCapacity(8);
  lightPath.setCapacity(8);
  const TechniqueSet vcm = TechniqueSet::parse("all;m=all");
  PathDensities d;
  std::vector<uint8_t> surface;
  // Every merge (vcm), and progressive photon mapping's merges at the first non-delta camera
  // vertex only, whose weights and sampleable bits both count the one merge there.
  for (const MergeSite site : {MergeSite::Every, MergeSite::FirstNonSpecular}) {
    const bool ppm = site == MergeSite::FirstNonSpecular;
    const MergeMis merge{4.0, ppm};
    Pcg32 rng(7, 11);
    int checked = 0, off = 0, behindDelta = 0;
    for (int i = 0; i < 4000; ++i) {
      const Vec2 pRaster(rng.next1D() * 64.f, rng.next1D() * 64.f);
      const int nt = generateCameraSubpath(scene, camera, pRaster, Vec2(0.5f), rng, WalkOptions{7, false}, cameraPath, counters);
      const int ns = generateLightSubpath(scene, rng, WalkOptions{6, false}, lightPath, counters);
      for (int t = 2; t <= nt; ++t) {
        const PathVertex& z = cameraPath[t - 1];
        if (ppm && t >= 3 && !cameraPath[t - 2].isDelta) break;  // where the render stops merging
        if (z.type != VertexType::Surface || z.isDelta) continue;
        for (int s = 2; s <= ns && s + t - 2 <= 6; ++s) {
          const PathVertex& y = lightPath[s - 1];
          if (y.type != VertexType::Surface || y.isDelta) continue;
          const BsdfEval f = cameraPath.bsdf(t - 1).eval(z.wo, y.wo, TransportMode::Radiance);
          const MergePdfs pdfs{f.pdfFwdW, f.pdfRevW};
          mergedPathDensities(lightPath.data(), s, cameraPath.data(), t, pdfs, d, surface);
          const MisPath path{lightPath.data(), s, cameraPath.data(), t - 1, nullptr, nullptr};
          const uint64_t bits = sampleableWithMerges(path, TechniqueKind::Merge, site);
          EXPECT_TRUE(bits >> Technique::merge(s, t).slot() & 1) << "the merge that formed the path";
          double sum = 0.0;
          for (const Technique x : techniquesOfLength(s + t - 2, TechniqueFamilies::All)) {
            const double w = weightWithMerges(d, surface, x, vcm, MisOptions{}, 1.f, 0.f, merge);
            if (!(bits >> x.slot() & 1)) {
              EXPECT_EQ(w, 0.0) << techniqueLabel(x) << " cannot sample this path";
              continue;
            }
            // A merge marked sampleable is one the weights count (none optimistic under ppm).
            if (x.isMerge()) {
              EXPECT_GT(w, 0.0) << techniqueLabel(x) << " is marked sampleable";
            }
            sum += w;
          }
          EXPECT_NEAR(mergeWeight(lightPath.data(), s, cameraPath.data(), t, pdfs, vcm, MisOptions{}, 1.f, 0.f, merge),
                      weightWithMerges(d, surface, Technique::merge(s, t), vcm, MisOptions{}, 1.f, 0.f, merge), 1e-6);
          ++checked;
          behindDelta += cameraPath[t - 2].isDelta ? 1 : 0;
          off += std::abs(sum - 1.0) > 1e-3;
        }
      }
    }
    EXPECT_GT(checked, ppm ? 300 : 1000);
    EXPECT_GT(behindDelta, 50);
    EXPECT_EQ(off, 0) << "of " << checked << " merge paths";
  }
}

}  // namespace
}  // namespace pathlab
