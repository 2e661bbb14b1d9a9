// The 3D view's camera and overlay (frustum, lights, light particles, the inspected path), depth range, colours.
#include "ui/inspect/view3d.h"

#include "core/math/rng.h"

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

namespace {

Vec3 boundsCentre(const Scene& scene) { return 0.5f * (scene.boundsMin() + scene.boundsMax()); }
float boundsDiagonal(const Scene& scene) { return std::max(glm::length(scene.boundsMax() - scene.boundsMin()), 1e-3f); }
Vec3 axisOf(const CameraDesc& c) { return glm::normalize(-Vec3(c.cameraToWorld[2])); }

// The render camera: its pyramid from the eye to the image's corners, cut at the depth of the
// scene's centre (so it reaches into the scene), and the image's rectangle there.
void addFrustum(InspectorOverlay& overlay, const Scene& scene, const RenderSettings& shown, const Camera& view) {
  if (shown.width <= 0 || shown.height <= 0) return;
  const CameraDesc desc = shown.camera.value_or(scene.cameraDesc());
  const Camera render(desc, shown.width, shown.height);  // a pinhole: the lens is a point here
  const Vec3 eye(desc.cameraToWorld[3]), axis = axisOf(desc);
  const float depth = std::max(glm::dot(boundsCentre(scene) - eye, axis), 0.1f * boundsDiagonal(scene));
  const Vec2 corners[4] = {{0.f, 0.f}, {static_cast<float>(shown.width), 0.f},
                           {static_cast<float>(shown.width), static_cast<float>(shown.height)},
                           {0.f, static_cast<float>(shown.height)}};
  Vec3 at[4];
  for (int i = 0; i < 4; ++i) {
    const Ray ray = render.generateRay(corners[i], Vec2(0.5f));
    at[i] = ray.o + ray.d * (depth / std::max(glm::dot(ray.d, axis), 1e-6f));
  }
  Vec3 from[4];  // the pinhole's eye, or an orthographic camera's film corners (a box, not a pyramid)
  for (int i = 0; i < 4; ++i) from[i] = render.generateRay(corners[i], Vec2(0.5f)).o;
  for (int i = 0; i < 4; ++i) {
    addOverlaySegment(overlay, view, from[i], at[i], SegmentRole::Frustum);
    addOverlaySegment(overlay, view, at[i], at[(i + 1) % 4], SegmentRole::Frustum);
  }
  // The image's top edge marked: a small triangle above it says which way is up.
  const Vec3 mid = 0.5f * (at[0] + at[1]), up = 0.15f * (at[0] - at[3]);
  addOverlaySegment(overlay, view, mid - 0.5f * up + 0.35f * (at[0] - mid), mid + up, SegmentRole::Frustum);
  addOverlaySegment(overlay, view, mid - 0.5f * up + 0.35f * (at[1] - mid), mid + up, SegmentRole::Frustum);
  if (const std::optional<Vec2> p = overlayPoint(view, eye)) overlay.markers.push_back({*p, VertexType::Camera, true, true});
}

void addPunctualLights(InspectorOverlay& overlay, const Scene& scene, const Camera& view) {
  for (size_t i = 0; i < scene.lights().size(); ++i) {
    const Light& light = scene.lights()[i];
    if (!light.isDeltaPosition()) continue;
    // A point or spot light's sample is its position whatever the reference point.
    const Vec3 p = light.sampleLi(boundsCentre(scene), Vec2(0.5f)).pLight;
    if (const std::optional<Vec2> r = overlayPoint(view, p)) overlay.markers.push_back({*r, VertexType::Light, true, false});
  }
}

void addParticles(InspectorOverlay& overlay, const LightParticles& particles, const Camera& view) {
  float brightest = 0.f;
  for (const std::vector<PathVertex>& subpath : particles.subpaths)
    for (const PathVertex& v : subpath) brightest = std::max(brightest, luminance(v.beta));
  if (!(brightest > 0.f)) return;
  for (const std::vector<PathVertex>& subpath : particles.subpaths)
    for (size_t i = 0; i + 1 < subpath.size(); ++i) {
      // The throughput carried along the segment (the light's own vertex: its emission per pdf).
      const float l = luminance(subpath[i].beta) / brightest;
      const float shade = l > 0.f ? std::clamp(1.f + std::log10(l) / 3.f, 0.f, 1.f) : 0.f;
      addOverlaySegment(overlay, view, subpath[i].p, subpath[i + 1].p, SegmentRole::Particle, shade);
    }
}

// Each watched chain's path polylines: light subpath, camera subpath, and the connection.
void addChainPath(InspectorOverlay& overlay, const MltChainPath& path, SegmentRole role, float hue, const Camera& view) {
  auto polyline = [&](const std::vector<Vec3>& p) {
    for (size_t i = 0; i + 1 < p.size(); ++i) addOverlaySegment(overlay, view, p[i], p[i + 1], role, hue);
  };
  polyline(path.light);
  polyline(path.camera);
  if (path.connected && !path.light.empty() && !path.camera.empty())
    addOverlaySegment(overlay, view, path.light.back(), path.camera.back(), role, hue);
}

void addChains(InspectorOverlay& overlay, const ChainPaths& chains, const Camera& view) {
  const std::vector<size_t> shown = chainsShown(chains);
  const size_t n = shown.size();
  // Faint first, so the solid moves and the thick current paths are drawn over them.
  for (const SegmentRole role : {SegmentRole::ChainRejected, SegmentRole::ChainAccepted, SegmentRole::ChainCurrent})
    for (size_t i = 0; i < n; ++i) {
      const float hue = static_cast<float>(i) / static_cast<float>(n);
      const MltWatchedChain& w = chains.summary->watched[shown[i]];
      if (role == SegmentRole::ChainCurrent) {
        addChainPath(overlay, w.current, role, hue, view);
        continue;
      }
      if (role == SegmentRole::ChainRejected && !chains.rejected) continue;
      for (const MltChainMove& m : w.moves)
        if (m.accepted == (role == SegmentRole::ChainAccepted)) addChainPath(overlay, m.proposal, role, hue, view);
    }
}

}  // namespace

std::vector<size_t> chainsShown(const ChainPaths& chains) {
  const size_t watched = chains.summary ? chains.summary->watched.size() : 0;
  const size_t n = std::min(watched, static_cast<size_t>(std::max(chains.count, 0)));
  std::vector<size_t> shown;
  for (size_t i = 0; i < n; ++i) shown.push_back((2 * i + 1) * watched / (2 * n));
  return shown;
}

void ensureView3DCamera(View3DState& state, const Scene& scene, const CameraDesc& renderCamera) {
  if (state.orbit && state.orbitScene == &scene) return;
  CameraDesc from = renderCamera;
  from.orthographic.reset();  // the view is a perspective one whatever the render camera
  OrbitCamera orbit(from, scene.boundsMin(), scene.boundsMax());
  orbit.orbit(0.61f, -0.3f);  // 35 degrees to the side, 17 from above
  orbit.zoom(-5.5f);          // 0.85^-5.5: about 2.5 times as far
  state.orbit = orbit;
  state.orbitScene = &scene;
}

CameraDesc view3DCameraDesc(const View3DState& state) {
  CameraDesc d = state.orbit ? state.orbit->desc() : CameraDesc{};
  d.aspectRatio.reset();
  d.orthographic.reset();  // the view is always a perspective one, whatever the render camera
  d.name = "3D view";
  return d;
}

Camera view3DCamera(const View3DState& state, Vec2i size) {
  return Camera(view3DCameraDesc(state), std::max(size.x, 1), std::max(size.y, 1));
}

Vec2 view3DDepthRange(const Scene& scene, const CameraDesc& view) {
  const Vec3 eye(view.cameraToWorld[3]), axis = axisOf(view);
  const Vec3 lo = scene.boundsMin(), hi = scene.boundsMax();
  float far = 0.f;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    far = std::max(far, glm::dot(corner - eye, axis));
  }
  const float diagonal = boundsDiagonal(scene);
  far = std::max(far * 1.02f, 1e-3f * diagonal);
  return {std::max(1e-4f * far, 1e-5f * diagonal), far};
}

bool refreshLightParticles(LightParticles& particles, const std::shared_ptr<const Scene>& scene,
                           const RenderSettings& settings, uint64_t passes) {
  if (!particles.on || !scene || passes == 0 || settings.width <= 0 || settings.height <= 0) return false;
  const int count = std::clamp(particles.count, 1, LightParticles::kMaxCount);
  const bool newReplay = !particles.replay || particles.scene != scene || particles.replay->settings() != settings;
  if (!newReplay && particles.pass == passes - 1 && particles.replayedCount == count) return false;
  if (newReplay) {
    // Built first, then kept with its scene: a refused one leaves the old pair intact.
    auto replay = std::make_unique<LightSubpathReplay>(*scene, settings);
    particles.replay = std::move(replay);
    particles.scene = scene;
  }
  particles.pass = passes - 1;
  particles.replayedCount = count;
  particles.subpaths.clear();
  if (settings.integrator == IntegratorKind::Pt) {
    particles.error = "the path tracer traces no light subpaths: switch to bpt or lt (I)";
    return true;
  }
  if (settings.integrator == IntegratorKind::Mlt) {
    // Its light subpaths are functions of the chains' primary numbers, not of a pass's streams:
    // the view draws the chains instead (ChainPaths).
    particles.error.clear();
    return true;
  }
  particles.error.clear();
  const uint64_t pixels = static_cast<uint64_t>(settings.width) * static_cast<uint64_t>(settings.height);
  for (int i = 0; i < count; ++i) {
    const uint64_t pixel = mixBits(particles.pass * 0x9E3779B97F4A7C15ull + static_cast<uint64_t>(i)) % pixels;
    const int x = static_cast<int>(pixel % static_cast<uint64_t>(settings.width));
    const int y = static_cast<int>(pixel / static_cast<uint64_t>(settings.width));
    std::vector<PathVertex> subpath = particles.replay->subpath(x, y, particles.pass);
    if (subpath.size() >= 2) particles.subpaths.push_back(std::move(subpath));
  }
  return true;
}

InspectorOverlay view3DOverlay(const View3DState& state, const PathInspectorState& inspector, const Scene& scene,
                               const RenderSettings& shown, const Camera& view) {
  InspectorOverlay overlay;
  addFrustum(overlay, scene, shown, view);
  addPunctualLights(overlay, scene, view);
  if (state.particles.on && state.chains.shown) addChains(overlay, state.chains, view);
  else if (state.particles.on) addParticles(overlay, state.particles, view);
  if (inspector.on && inspector.result) {
    const InspectorOverlay paths = inspectorOverlay(inspector, view);
    overlay.segments.insert(overlay.segments.end(), paths.segments.begin(), paths.segments.end());
    overlay.markers.insert(overlay.markers.end(), paths.markers.begin(), paths.markers.end());
  }
  return overlay;
}

std::vector<PreviewColour> previewColours(const Scene& scene) {
  std::vector<std::optional<Vec4>> averages(scene.textures().size());
  auto textureAverage = [&](const TextureRef& ref) {
    if (!ref.valid()) return Vec4(1.f);
    std::optional<Vec4>& a = averages[static_cast<size_t>(ref.texture)];
    if (!a) a = scene.textures()[static_cast<size_t>(ref.texture)].average();
    return *a;
  };
  std::vector<PreviewColour> colours;
  for (const Material& m : scene.materials()) {
    const Vec3 emission = Vec3(m.emissiveFactor) * m.emissiveStrength * Vec3(textureAverage(m.emissiveTexture));
    const float peak = std::max({emission.x, emission.y, emission.z});
    if (peak > 0.f) {
      colours.push_back({Vec4(emission / peak, 1.f), true});
      continue;
    }
    const Vec4 base = m.baseColorFactor * textureAverage(m.baseColorTexture);
    float alpha = m.alphaMode == AlphaMode::Blend ? base.a : 1.f;
    if (m.transmissionFactor > 0.f) alpha = std::min(alpha, 0.3f);  // glass and media: see the paths inside
    colours.push_back({Vec4(Vec3(base), alpha), false});
  }
  return colours;
}

}  // namespace pathlab::ui
