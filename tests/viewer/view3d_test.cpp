// The 3D view without a window (ui/inspect/view3d.h): the light particles are the light subpaths the render
// traced (replayed from the same streams as the inspector's full replay), start on an emitter and
// are replayed only when the pass or the settings change; the view's overlay shows the render
// camera where it is and the inspected sample's vertices where its own camera sees them; the
// depth range holds the scene; materials get their preview colours; a Metropolis image's watched
// chains are drawn in place of the particles, segment for segment of their paths.
#include "ui/inspect/view3d.h"

#include "core/render/render_session.h"
#include "core/render/sample_inspection.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace pathlab::ui {
namespace {

std::shared_ptr<const Scene> sharedBox() {
  static const std::shared_ptr<const Scene> scene =
      std::make_shared<const Scene>(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  return scene;
}

RenderSettings particleBoxSettings() {
  RenderSettings s;
  s.width = 64;
  s.height = 64;
  s.maxLength = 5;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

TEST(View3D, ParticlesAreTheLightSubpathsTheRenderTraced) {
  const RenderSettings s = particleBoxSettings();
  const RenderSession session(*sharedBox(), s);
  const LightSubpathReplay replay(*sharedBox(), s);
  int compared = 0;
  for (int i = 0; i < 40; ++i) {
    const int x = (i * 37) % s.width, y = (i * 11) % s.height;
    const uint64_t pass = static_cast<uint64_t>(i % 5);
    const std::vector<PathVertex> particle = replay.subpath(x, y, pass);
    const SampleInspection full = inspectSample(session, x, y, pass);
    ASSERT_EQ(particle.size(), full.trace.lightSubpath.size()) << x << "," << y << " pass " << pass;
    for (size_t v = 0; v < particle.size(); ++v) {
      EXPECT_EQ(particle[v].p, full.trace.lightSubpath[v].p);
      EXPECT_EQ(particle[v].beta, full.trace.lightSubpath[v].beta);
    }
    if (!particle.empty()) {
      EXPECT_EQ(particle.front().type, VertexType::Light);  // it starts on the emitter
      ++compared;
    }
  }
  EXPECT_GT(compared, 30);
  RenderSettings pt = s;
  pt.integrator = IntegratorKind::Pt;
  EXPECT_TRUE(LightSubpathReplay(*sharedBox(), pt).subpath(3, 4, 0).empty());
}

TEST(View3D, ParticlesAreReplayedOncePerPassAndSettings) {
  LightParticles particles;
  particles.count = 16;
  const RenderSettings s = particleBoxSettings();
  EXPECT_FALSE(refreshLightParticles(particles, sharedBox(), s, 3));  // off
  particles.on = true;
  EXPECT_FALSE(refreshLightParticles(particles, sharedBox(), s, 0));  // no pass finished yet
  ASSERT_TRUE(refreshLightParticles(particles, sharedBox(), s, 3));
  EXPECT_EQ(particles.pass, 2u);
  EXPECT_GT(particles.subpaths.size(), 8u);
  EXPECT_LE(particles.subpaths.size(), 16u);
  const std::vector<std::vector<PathVertex>> first = particles.subpaths;
  EXPECT_FALSE(refreshLightParticles(particles, sharedBox(), s, 3));
  ASSERT_TRUE(refreshLightParticles(particles, sharedBox(), s, 4));
  EXPECT_NE(first.front().back().p, particles.subpaths.front().back().p);  // another pass, other paths
  RenderSettings pt = s;
  pt.integrator = IntegratorKind::Pt;
  EXPECT_TRUE(refreshLightParticles(particles, sharedBox(), pt, 4));
  EXPECT_TRUE(particles.subpaths.empty());
  EXPECT_NE(particles.error.find("path tracer"), std::string::npos);
}

TEST(View3D, OverlayShowsTheRenderCameraAndTheSampleWhereTheViewSeesThem) {
  const Scene& scene = *sharedBox();
  const RenderSettings s = particleBoxSettings();
  View3DState state;
  ensureView3DCamera(state, scene, scene.cameraDesc());
  ASSERT_TRUE(state.orbit.has_value());
  const Vec2i size(400, 300);
  const Camera view = view3DCamera(state, size);
  // The view is pulled back: the render camera's eye and the whole scene are in front of it, on its film.
  const Vec3 eye(scene.cameraDesc().cameraToWorld[3]);
  const std::optional<Vec2> eyeAt = overlayPoint(view, eye);
  ASSERT_TRUE(eyeAt.has_value());
  auto onFilm = [&](Vec2 p) { return p.x >= 0.f && p.y >= 0.f && p.x < 400.f && p.y < 300.f; };
  EXPECT_TRUE(onFilm(*eyeAt)) << eyeAt->x << "," << eyeAt->y;
  EXPECT_TRUE(onFilm(*overlayPoint(view, 0.5f * (scene.boundsMin() + scene.boundsMax()))));

  PathInspectorState inspector;
  inspector.on = true;
  inspector.pick = Vec2(0.3f, 0.7f);
  ASSERT_TRUE(refreshInspection(inspector, scene, s));
  const InspectorOverlay overlay = view3DOverlay(state, inspector, scene, s, view);
  auto hasMarker = [&](Vec2 at, VertexType type) {
    return std::any_of(overlay.markers.begin(), overlay.markers.end(), [&](const InspectorMarker& m) {
      return m.type == type && glm::length(m.p - at) < 1e-3f;
    });
  };
  EXPECT_TRUE(hasMarker(*eyeAt, VertexType::Camera));
  int frustum = 0;
  for (const InspectorSegment& seg : overlay.segments) frustum += seg.role == SegmentRole::Frustum ? 1 : 0;
  EXPECT_GE(frustum, 8);  // four edges from the eye, four around the image
  // Every vertex of both subpaths where the view's camera sees it (the render camera would put
  // the camera subpath's vertices elsewhere).
  const SampleTrace& trace = inspector.result->trace;
  ASSERT_GE(trace.cameraSubpath.size(), 2u);
  for (const std::vector<PathVertex>* subpath : {&trace.cameraSubpath, &trace.lightSubpath})
    for (const PathVertex& v : *subpath) EXPECT_TRUE(hasMarker(*overlayPoint(view, v.p), v.type)) << v.p.x;
  const Camera render(scene.cameraDesc(), s.width, s.height);
  EXPECT_GT(glm::length(*overlayPoint(view, trace.cameraSubpath[1].p) - *overlayPoint(render, trace.cameraSubpath[1].p)), 1.f);
}

TEST(View3D, DepthRangeHoldsTheSceneAndColoursFollowTheMaterials) {
  const Scene& scene = *sharedBox();
  View3DState state;
  ensureView3DCamera(state, scene, scene.cameraDesc());
  const CameraDesc view = view3DCameraDesc(state);
  const Vec2 range = view3DDepthRange(scene, view);
  const Vec3 eye(view.cameraToWorld[3]), axis = glm::normalize(-Vec3(view.cameraToWorld[2]));
  EXPECT_GT(range.x, 0.f);
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? scene.boundsMax().x : scene.boundsMin().x, (i & 2) ? scene.boundsMax().y : scene.boundsMin().y,
                      (i & 4) ? scene.boundsMax().z : scene.boundsMin().z);
    const float depth = glm::dot(corner - eye, axis);
    EXPECT_GT(depth, range.x);
    EXPECT_LT(depth, range.y);
  }
  int emitters = 0;
  const std::vector<PreviewColour> colours = previewColours(scene);
  ASSERT_EQ(colours.size(), scene.materials().size());
  for (size_t m = 0; m < scene.materials().size(); ++m) {
    const PreviewColour& c = colours[m];
    const Material& material = scene.material(static_cast<int>(m));
    if (c.emitter) {
      ++emitters;
      EXPECT_FLOAT_EQ(std::max({c.rgba.r, c.rgba.g, c.rgba.b}), 1.f);  // the emission's colour, full brightness
    } else {
      EXPECT_FLOAT_EQ(c.rgba.r, material.baseColorFactor.r);
    }
  }
  EXPECT_EQ(emitters, 1);
}

TEST(View3D, MetropolisChainsAreDrawnSegmentForSegmentOfTheirPaths) {
  const Scene& scene = *sharedBox();
  RenderSettings s = particleBoxSettings();
  s.width = s.height = 24;
  s.integrator = IntegratorKind::Mlt;
  s.mlt.chains = 64;
  s.mlt.bootstrap = 2000;
  RenderSession session(scene, s);
  session.metropolis()->setWatchedChains(8);
  session.renderPass();
  session.renderPass();
  View3DState state;
  ensureView3DCamera(state, scene, scene.cameraDesc());
  // Far enough back that every vertex is in front of the view's lens: no segment is clipped away.
  state.orbit->zoom(-8.f);
  const Camera view = view3DCamera(state, Vec2i(400, 300));
  state.particles.on = true;
  state.chains.shown = true;
  state.chains.summary = std::make_shared<const MltSummary>(session.metropolis()->summary());
  ASSERT_EQ(state.chains.summary->watched.size(), 8u);
  state.chains.count = 3;
  const std::vector<size_t> shown = chainsShown(state.chains);
  EXPECT_EQ(shown, (std::vector<size_t>{1, 4, 6}));  // spread over the watched ones
  auto segments = [](const MltChainPath& p) {
    const size_t light = p.light.empty() ? 0 : p.light.size() - 1, camera = p.camera.empty() ? 0 : p.camera.size() - 1;
    return light + camera + (p.connected && !p.light.empty() && !p.camera.empty() ? 1 : 0);
  };
  size_t current = 0, accepted = 0, rejected = 0;
  for (const size_t i : shown) {
    const MltWatchedChain& w = state.chains.summary->watched[i];
    current += segments(w.current);
    for (const MltChainMove& m : w.moves) (m.accepted ? accepted : rejected) += segments(m.proposal);
  }
  ASSERT_GT(current, 0u);
  PathInspectorState inspector;
  auto count = [&](SegmentRole role) {
    const InspectorOverlay overlay = view3DOverlay(state, inspector, scene, s, view);
    return static_cast<size_t>(std::count_if(overlay.segments.begin(), overlay.segments.end(),
                                             [&](const InspectorSegment& x) { return x.role == role; }));
  };
  EXPECT_EQ(count(SegmentRole::ChainCurrent), current);
  EXPECT_EQ(count(SegmentRole::ChainAccepted), accepted);
  EXPECT_EQ(count(SegmentRole::ChainRejected), rejected);
  EXPECT_EQ(count(SegmentRole::Particle), 0u);  // the chains replace the particles
  state.chains.rejected = false;
  EXPECT_EQ(count(SegmentRole::ChainRejected), 0u);
  state.particles.on = false;
  EXPECT_EQ(count(SegmentRole::ChainCurrent), 0u);
}

}  // namespace
}  // namespace pathlab::ui
