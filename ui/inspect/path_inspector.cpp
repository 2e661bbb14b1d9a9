// The picked sample replayed (and the brightest of the first n found), and the overlay of its selected path.
#include "ui/inspect/path_inspector.h"

#include "core/bpt/variance_aware_mis.h"
#include "core/math/frame.h"
#include "core/render/outlier_replay.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace pathlab::ui {

namespace {

// Points closer to the lens than this (in camera space, along the view direction) are cut off: a
// segment through the lens plane has no projection.
constexpr float kNearDepth = 1e-4f;

}  // namespace

void addOverlaySegment(InspectorOverlay& overlay, const Camera& camera, const Vec3& a, const Vec3& b, SegmentRole role,
                       float shade) {
  Vec3 ca = camera.toCameraSpace(a), cb = camera.toCameraSpace(b);
  const float da = -ca.z, db = -cb.z;
  if (!(da > kNearDepth) && !(db > kNearDepth)) return;  // wholly behind the lens
  // Clip the part behind the near plane (depth kNearDepth) away.
  if (da < kNearDepth) ca = cb + (ca - cb) * ((db - kNearDepth) / (db - da));
  else if (db < kNearDepth) cb = ca + (cb - ca) * ((da - kNearDepth) / (da - db));
  overlay.segments.push_back({camera.rasterOfCameraPoint(ca), camera.rasterOfCameraPoint(cb), role, shade});
}

std::optional<Vec2> overlayPoint(const Camera& camera, const Vec3& p) {
  const Vec3 c = camera.toCameraSpace(p);
  if (!(-c.z > kNearDepth)) return std::nullopt;
  return camera.rasterOfCameraPoint(c);
}

std::vector<Vec3> mergeDiskPoints(const MergedVertices& m, int n) {
  const Frame frame(glm::normalize(m.cameraNormal != Vec3(0.f) ? m.cameraNormal : Vec3(0.f, 0.f, 1.f)));
  std::vector<Vec3> rim;
  for (int i = 0; i < n; ++i) {
    const float phi = 2.f * kPi * static_cast<float>(i) / static_cast<float>(n);
    rim.push_back(m.camera + m.radius * frame.toWorld(Vec3(std::cos(phi), std::sin(phi), 0.f)));
  }
  return rim;
}

namespace {

void addSubpath(InspectorOverlay& overlay, const Camera& camera, const std::vector<PathVertex>& subpath, bool cameraSide) {
  for (size_t i = 0; i + 1 < subpath.size(); ++i)
    addOverlaySegment(overlay, camera, subpath[i].p, subpath[i + 1].p,
               cameraSide ? SegmentRole::CameraSubpath : SegmentRole::LightSubpath);
  for (const PathVertex& v : subpath)
    if (const std::optional<Vec2> p = overlayPoint(camera, v.p))
      overlay.markers.push_back({*p, v.type, v.isDelta || v.isDeltaPosition, cameraSide});
}

}  // namespace

bool refreshInspection(PathInspectorState& state, const Scene& scene, const RenderSettings& shown) {
  if (state.pinned) {
    if (!state.pinnedShown) state.pinnedShown = shown;
    else if (!sameExceptSize(*state.pinnedShown, shown)) state.pinned.reset(), state.pinnedShown.reset();
  }
  const RenderSettings& settings = state.pinned ? *state.pinned : shown;
  if (!state.on || !state.pick || settings.width <= 0 || settings.height <= 0) return false;
  state.pixel = Vec2i(std::clamp(static_cast<int>(state.pick->x * static_cast<float>(settings.width)), 0, settings.width - 1),
                      std::clamp(static_cast<int>(state.pick->y * static_cast<float>(settings.height)), 0, settings.height - 1));
  if (state.result && state.inspectedPixel == state.pixel && state.inspectedSample == state.sample &&
      state.inspectedSettings == settings && state.inspectedScene == &scene)
    return false;
  state.inspectedPixel = state.pixel;
  state.inspectedSample = state.sample;
  state.inspectedSettings = settings;
  state.inspectedScene = &scene;
  state.result.reset();
  state.selected = -1;
  const std::optional<Outlier> focus = std::exchange(state.focus, std::nullopt);
  if (settings.integrator == IntegratorKind::Pt) {
    state.error = "the path tracer has no (s,t) techniques to inspect: switch to bpt or lt (I)";
    return false;
  }
  if (settings.integrator == IntegratorKind::Mlt) {
    // A pixel's value is the chains' visits, not independent samples of its own to replay.
    state.error = "Metropolis has no per-pixel samples to replay: switch to bpt or lt to inspect one";
    return false;
  }
  if (settings.mis.heuristic == MisHeuristic::VarianceAware && state.sample >= kVarianceAwarePilotPasses) {
    // Pass N was weighed with factors from passes 0 .. N-1, which a replay here does not have.
    state.error = fmt::format(
        "variance-aware MIS weighs sample {} with the factors of the passes before it, which a replay here does not "
        "have: inspect samples 0-{} (the balance heuristic's pilot passes) here, or this one with `pathlab inspect "
        "--mis variance-aware --sample {}`",
        state.sample, kVarianceAwarePilotPasses - 1, state.sample);
    return false;
  }
  if (settings.lightPathsAuto && state.sample >= static_cast<uint64_t>(kLightPathPilotPasses)) {
    // Pass N ran at the light subpath count that passes 0 .. N-1 chose, which a replay here does not know.
    state.error = fmt::format(
        "--light-paths auto renders sample {} at the light subpaths the passes before it chose, which a replay "
        "here does not have: inspect samples 0-{} (the pilot passes, F = 1) here, or this one with `pathlab "
        "inspect --light-paths auto --sample {}`",
        state.sample, kLightPathPilotPasses - 1, state.sample);
    return false;
  }
  const Vec2i p = *state.pixel;
  state.error.clear();
  const RenderSession session(scene, settings);
  state.result = inspectSample(session, p.x, p.y, state.sample);
  // Select the technique that gave the sample most (the one a firefly hunt wants to see).
  float best = 0.f;
  const std::vector<TechniqueResult>& records = state.result->trace.records;
  for (size_t i = 0; i < records.size(); ++i) {
    const float l = luminance(records[i].unweighted * records[i].weight);
    if (l > best) best = l, state.selected = static_cast<int>(i);
  }
  // An outlier opened from the list: its own record, found as `pathlab outliers` finds it.
  if (focus && focus->id.x == p.x && focus->id.y == p.y && focus->id.sample == state.sample)
    if (const int record = outlierRecord(state.result->trace, *focus); record >= 0) state.selected = record;
  return true;
}

uint64_t brightestSearchCount(const RenderSettings& settings) {
  return covers(enabledTechniques(settings).families(), TechniqueKind::Merge) ? 16 : 256;
}

uint64_t brightestSample(const Scene& scene, const RenderSettings& settings, Vec2i pixel, uint64_t n) {
  const RenderSession session(scene, settings);
  uint64_t best = 0;
  float bestLum = -1.f;
  for (uint64_t i = 0; i < n; ++i) {
    const SampleInspection s = inspectSample(session, pixel.x, pixel.y, i);
    float l = luminance(s.cameraEstimate);
    for (const TechniqueResult& r : s.trace.records)
      if (r.t == 1) l += luminance(r.unweighted * r.weight);  // its splats count too, wherever they land
    if (l > bestLum) bestLum = l, best = i;
  }
  return best;
}

InspectorOverlay inspectorOverlay(const PathInspectorState& state, const Camera& camera) {
  InspectorOverlay overlay;
  if (!state.result) return overlay;
  const SampleTrace& trace = state.result->trace;
  addSubpath(overlay, camera, trace.cameraSubpath, true);
  addSubpath(overlay, camera, trace.lightSubpath, false);
  // Each technique's connection edge x_{s-1} -- x_s (s = 0 connects nothing: the camera subpath
  // hits the emitter).
  for (size_t i = 0; i < trace.records.size() && i < trace.paths.size(); ++i) {
    const TechniqueResult& r = trace.records[i];
    const TracedPath& path = trace.paths[i];
    if (r.s < 1 || path.size() < 2 || static_cast<int>(path.size()) != r.s + r.t) continue;
    addOverlaySegment(overlay, camera, path.p[static_cast<size_t>(r.s - 1)], path.p[static_cast<size_t>(r.s)],
               r.blocked() ? SegmentRole::BlockedConnection : SegmentRole::Connection);
  }
  if (state.selected >= 0 && static_cast<size_t>(state.selected) < trace.paths.size()) {
    const TracedPath& path = trace.paths[static_cast<size_t>(state.selected)];
    for (size_t v = 0; v + 1 < path.size(); ++v) addOverlaySegment(overlay, camera, path.p[v], path.p[v + 1], SegmentRole::Selected);
    const TechniqueResult& r = trace.records[static_cast<size_t>(state.selected)];
    if (r.kind == TechniqueKind::Merge) {
      const std::vector<Vec3> rim = mergeDiskPoints(r.merged);
      for (size_t i = 0; i < rim.size(); ++i)
        addOverlaySegment(overlay, camera, rim[i], rim[(i + 1) % rim.size()], SegmentRole::MergeDisk);
      addOverlaySegment(overlay, camera, r.merged.camera, r.merged.light, SegmentRole::MergeDisk);
    }
  }
  return overlay;
}

}  // namespace pathlab::ui
