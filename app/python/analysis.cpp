// pathlab.inspect, Renderer.technique_maps, Renderer.variance_maps and Renderer.outliers.
#include "app/python/analysis.h"

#include "app/python/arguments.h"
#include "core/maps/technique_maps.h"
#include "core/render/inspection_report.h"
#include "core/render/outlier_replay.h"
#include "core/render/sample_inspection.h"
#include "core/render/technique_luminance.h"

#include <pybind11/numpy.h>

#include <fmt/core.h>

namespace py = pybind11;

namespace pathlab::python {

py::object techniqueKey(Technique x) {
  if (x.isMerge()) return py::make_tuple("M", x.s, x.t);
  if (x.isEquiangular()) return py::make_tuple("E", x.s, x.t);
  return py::make_tuple(x.s, x.t);
}

py::object inspect(const LoadedScene& scene, const PySettings& settings, const py::object& pixelArgument,
                   const py::object& sampleArgument) {
  app::RenderOptions o = settings.options;
  RenderSettings& s = o.estimator.settings;
  if (s.integrator == IntegratorKind::Pt || s.integrator == IntegratorKind::Mlt)
    throw Error("inspect replays one independent bidirectional sample: use integrator bpt or lt");
  if (!py::isinstance<py::sequence>(pixelArgument) || py::isinstance<py::str>(pixelArgument) || py::len(pixelArgument) != 2)
    throw Error("inspect: pixel must be (x, y)");
  const py::sequence xy = pixelArgument.cast<py::sequence>();
  const std::pair<int, int> pixel{static_cast<int>(intArgument(xy[0], "inspect: pixel x", INT32_MIN, INT32_MAX)),
                                  static_cast<int>(intArgument(xy[1], "inspect: pixel y", INT32_MIN, INT32_MAX))};
  const uint64_t sample = static_cast<uint64_t>(intArgument(sampleArgument, "inspect: sample", 0, app::kMaxSpp - 1));
  nlohmann::json json;
  try {
    app::sizeRenderForScene(o, scene.scene->cameraDesc());
    const auto [x, y] = pixel;
    if (x < 0 || y < 0 || x >= s.width || y >= s.height)
      throw Error(fmt::format("inspect: pixel ({}, {}) is outside the {} x {} image", x, y, s.width, s.height));
    // As `pathlab inspect`: a session of its own, the sample replayed in it.
    RenderSession session(*scene.scene, s);
    json = inspectionJson(s, inspectSample(session, x, y, sample));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
  return py::module_::import("json").attr("loads")(json.dump());
}

py::object check(const LoadedScene& scene, const PySettings& settings, const py::kwargs& kwargs) {
  app::CheckCommandOptions o = checkFromArguments(settings.words, kwargs);
  warnAbout(*scene.scene, o.estimator.settings);
  nlohmann::json json;
  std::atomic<bool> stop{false};
  PassThread thread;
  try {
    const bool interrupted = runWatchingForCtrlC(
        thread,
        [&] {
          const app::ThreadLimit threads(o.threads);
          json = app::checkOutcomeJson(app::checkScene(o, *scene.scene, false, &stop), scene.path);
        },
        stop);
    if (interrupted) throw py::error_already_set();
  } catch (const app::CheckStopped&) {
    throw py::error_already_set();
  } catch (const py::error_already_set&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
  return py::module_::import("json").attr("loads")(json.dump());
}

namespace {
// Every technique's key up to `length`, in index order (the maps' 'techniques').
py::list techniqueKeys(int length) {
  py::list keys;
  for (size_t i = 0; i < Technique::countUpTo(length); ++i) keys.append(techniqueKey(Technique::fromIndex(i)));
  return keys;
}
}  // namespace

py::dict techniqueMapsOf(const Renderer& r) {
  const RenderSettings& s = r.settings();
  if (!s.techniqueMaps)
    throw Error("technique_maps: the renderer keeps no maps (Settings(technique_maps=L) keeps those up to length L)");
  const int length = r.techniqueMapLength();
  const TechniqueLuminance lum = techniqueLuminance(r.session("technique_maps"), length);
  py::dict out;
  out["techniques"] = techniqueKeys(length);
  // The dominant technique of every length together (key None) and of each length k.
  py::dict dominant, dominantShare;
  for (int k = 0; k <= length; ++k) {
    DominantMap m = dominantMap(lum, k);
    const py::object key = k == 0 ? py::object(py::none()) : py::object(py::int_(k));
    std::vector<int32_t> index(m.technique.begin(), m.technique.end());
    dominant[key] = ownedArray(std::move(index), {m.height, m.width});
    dominantShare[key] = ownedArray(std::move(m.share), {m.height, m.width});
  }
  out["dominant"] = dominant;
  out["dominant_share"] = dominantShare;
  py::dict share, cannot;
  for (const Technique x : techniquesUpTo(length, lum.families)) {
    share[techniqueKey(x)] = ownedArray(shareMap(lum, x), {lum.height, lum.width});
    CannotSampleMap c = cannotSampleMap(lum, x);
    cannot[techniqueKey(x)] = ownedArray(std::move(c.unreachable), {c.height, c.width});
  }
  out["share"] = share;
  out["cannot_sample"] = cannot;
  if (covers(lum.families, TechniqueKind::Merge))
    out["merges_share"] = ownedArray(familyShareMap(lum, TechniqueKind::Merge), {lum.height, lum.width});
  return out;
}

py::dict varianceMapsOf(const Renderer& r) {
  if (!r.settings().varianceMaps)
    throw Error("variance_maps: the renderer keeps no variance maps (Settings(variance_maps=L) keeps those up to length L)");
  const int length = r.varianceMapLength();
  const TechniqueLuminance lum = techniqueLuminance(r.session("variance_maps"), length);
  py::dict out;
  out["techniques"] = techniqueKeys(length);
  py::dict variance;
  for (const Technique x : techniquesUpTo(length, lum.families)) {
    std::vector<float> v = lum.variance[x.index()];
    variance[techniqueKey(x)] = ownedArray(std::move(v), {lum.height, lum.width});
  }
  out["variance"] = variance;
  DominantMap m = dominantVarianceMap(lum);
  std::vector<int32_t> index(m.technique.begin(), m.technique.end());
  out["dominant"] = ownedArray(std::move(index), {m.height, m.width});
  out["dominant_share"] = ownedArray(std::move(m.share), {m.height, m.width});
  return out;
}

py::list outliersOf(const Renderer& r) {
  const RenderSession& session = r.session("outliers");
  const Image image = session.image();
  py::list out;
  const py::object loads = py::module_::import("json").attr("loads");
  for (const Outlier& o : session.outliers()) {
    const ReplayedOutlier replayed = replayOutlier(session, o);
    out.append(loads(outlierJson(session.settings(), replayed, outlierShareOfPixel(o, image, session.passes())).dump()));
  }
  return out;
}

}  // namespace pathlab::python
