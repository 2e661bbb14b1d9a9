// The viewer's path inspector without a window (ui/inspect/path_inspector.h): a picked pixel's sample is
// replayed once per change of pixel, sample, settings or scene, never for the path tracer; its
// overlay projects the subpaths and connections through the render camera, the camera subpath's
// first hit onto the picked pixel, and clips what lies behind the lens.
#include "ui/inspect/path_inspector.h"

#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

RenderSettings boxSettings() {
  RenderSettings s;
  s.width = 120;
  s.height = 120;
  s.maxLength = 4;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

TEST(PathInspector, ReplaysOnlyWhenSomethingChanged) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  const RenderSettings s = boxSettings();
  PathInspectorState state;
  EXPECT_FALSE(refreshInspection(state, scene, s));  // off
  state.on = true;
  EXPECT_FALSE(refreshInspection(state, scene, s));  // no pixel yet
  state.pick = Vec2(40.5f / 120.f, 80.5f / 120.f);  // pixel (40, 80)
  ASSERT_TRUE(refreshInspection(state, scene, s));
  EXPECT_EQ(state.pixel, Vec2i(40, 80));
  ASSERT_TRUE(state.result.has_value());
  EXPECT_EQ(state.result->x, 40);
  EXPECT_FALSE(refreshInspection(state, scene, s));  // nothing changed
  state.sample = 3;
  EXPECT_TRUE(refreshInspection(state, scene, s));
  EXPECT_EQ(state.result->sample, 3u);
  RenderSettings power = s;
  power.mis.heuristic = MisHeuristic::Power;
  EXPECT_TRUE(refreshInspection(state, scene, power));
  RenderSettings pt = s;
  pt.integrator = IntegratorKind::Pt;
  EXPECT_FALSE(refreshInspection(state, scene, pt));
  EXPECT_FALSE(state.result.has_value());
  EXPECT_NE(state.error.find("path tracer"), std::string::npos);
}

TEST(PathInspector, OverlayProjectsThePathsThroughTheRenderCamera) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  const RenderSettings s = boxSettings();
  const Camera camera(scene.cameraDesc(), s.width, s.height);
  int withConnections = 0;
  for (int i = 0; i < 12; ++i) {
    PathInspectorState state;
    state.on = true;
    state.pick = Vec2((10.5f + 8.f * static_cast<float>(i)) / 120.f, 60.5f / 120.f);
    ASSERT_TRUE(refreshInspection(state, scene, s));
    const SampleTrace& trace = state.result->trace;
    const InspectorOverlay overlay = inspectorOverlay(state, camera);
    int cameraSegments = 0, lightSegments = 0, connections = 0;
    for (const InspectorSegment& seg : overlay.segments) {
      cameraSegments += seg.role == SegmentRole::CameraSubpath;
      lightSegments += seg.role == SegmentRole::LightSubpath;
      connections += seg.role == SegmentRole::Connection || seg.role == SegmentRole::BlockedConnection;
    }
    EXPECT_EQ(cameraSegments, std::max(trace.cameraVertices - 1, 0));
    EXPECT_EQ(lightSegments, std::max(trace.lightVertices - 1, 0));
    int expected = 0;
    for (size_t r = 0; r < trace.records.size(); ++r)
      expected += trace.records[r].s >= 1 && trace.paths[r].size() >= 2 ? 1 : 0;
    EXPECT_EQ(connections, expected);
    withConnections += connections > 0;
    // The primary ray is seen end on: the camera subpath's first hit projects onto the picked
    // pixel (within the pixel: the sample's position inside it is random).
    ASSERT_GE(trace.cameraVertices, 2);
    const std::optional<Vec2> hit = camera.rasterPosition(trace.cameraSubpath[1].p);
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->x, static_cast<float>(state.pixel->x) + 0.5f, 0.51f);
    EXPECT_NEAR(hit->y, static_cast<float>(state.pixel->y) + 0.5f, 0.51f);
    // Every drawn endpoint is finite (clipped in front of the lens).
    for (const InspectorSegment& seg : overlay.segments)
      EXPECT_TRUE(std::isfinite(seg.a.x) && std::isfinite(seg.a.y) && std::isfinite(seg.b.x) && std::isfinite(seg.b.y));
  }
  EXPECT_GT(withConnections, 6);
}

// A selected merge draws its disk: the rim at the pass's radius about the camera vertex, in the
// plane its normal sets, with the light vertex inside, projected like the paths.
TEST(PathInspector, ASelectedMergeDrawsItsDiskAtTheMergedVertex) {
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-spheres.gltf"));
  RenderSettings s = boxSettings();
  s.width = s.height = 64;
  s.techniques = TechniqueSet::parse("all;m=all");  // --integrator vcm
  s.mergeRadius = 0.05f;
  const Camera camera(scene.cameraDesc(), s.width, s.height);
  int disks = 0;
  for (int i = 0; i < 8 && disks < 3; ++i) {
    PathInspectorState state;
    state.on = true;
    state.pick = Vec2((8.5f + 6.f * static_cast<float>(i)) / 64.f, 40.5f / 64.f);
    ASSERT_TRUE(refreshInspection(state, scene, s));
    const std::vector<TechniqueResult>& records = state.result->trace.records;
    for (size_t r = 0; r < records.size(); ++r) {
      if (records[r].kind != TechniqueKind::Merge) continue;
      const MergedVertices& m = records[r].merged;
      ASSERT_GT(m.radius, 0.f);
      EXPECT_LE(glm::length(m.light - m.camera), m.radius * 1.0001f);
      const std::vector<Vec3> rim = mergeDiskPoints(m);
      for (const Vec3& p : rim) {
        EXPECT_NEAR(glm::length(p - m.camera), m.radius, 1e-4f * m.radius);
        EXPECT_NEAR(glm::dot(p - m.camera, glm::normalize(m.cameraNormal)), 0.f, 1e-4f * m.radius);
      }
      state.selected = static_cast<int>(r);
      int diskSegments = 0;
      for (const InspectorSegment& seg : inspectorOverlay(state, camera).segments)
        diskSegments += seg.role == SegmentRole::MergeDisk;
      EXPECT_EQ(diskSegments, static_cast<int>(rim.size()) + 1);  // the rim and the step to the light vertex
      ++disks;
      break;
    }
  }
  EXPECT_GE(disks, 3);
}

}  // namespace
}  // namespace pathlab::ui
