// The pathlab Python module (issue 36): scenes, settings, progressive renders as NumPy arrays,
// the technique pyramid and the counters, with the command line's options and messages.
#include "app/python/analysis.h"
#include "app/python/arguments.h"
#include "app/python/converge.h"
#include "app/python/renderer.h"
#include "core/bpt/technique_set.h"
#include "core/render/render_settings.h"
#include "core/sampling/technique_label.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/core.h>

namespace py = pybind11;
using namespace pathlab;
using namespace pathlab::python;

namespace {

py::tuple vec3(const Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

py::dict cameraOf(const CameraDesc& c) {
  py::dict d;
  py::list toWorld;
  for (int row = 0; row < 4; ++row)
    toWorld.append(py::make_tuple(c.cameraToWorld[0][row], c.cameraToWorld[1][row], c.cameraToWorld[2][row],
                                  c.cameraToWorld[3][row]));
  d["camera_to_world"] = toWorld;
  d["name"] = c.name;
  if (c.orthographic) d["orthographic"] = py::make_tuple(c.orthographic->x, c.orthographic->y);
  else d["yfov"] = c.yfov;
  d["aspect_ratio"] = c.aspectRatio ? py::cast(*c.aspectRatio) : py::none();
  return d;
}

std::string settingsRepr(const PySettings& s) {
  const RenderSettings& r = s.options.estimator.settings;
  return fmt::format("pathlab.Settings(integrator={}, techniques='{}', max_length={}, mis={}, seed={}, size={})",
                     s.options.estimator.integrator, enabledTechniques(r).toString(), r.maxLength,
                     misHeuristicName(r.mis.heuristic), r.seed,
                     s.options.size.width > 0 || s.options.size.height > 0
                         ? fmt::format("{}x{}", s.options.size.width, s.options.size.height)
                         : std::string("the camera's"));
}

}  // namespace

PYBIND11_MODULE(pathlab, m) {
  m.doc() = "pathlab: the path integral's techniques (s,t), their densities and weights, from Python";
  static py::exception<Error> error(m, "Error");
  error.doc() = "A refused argument or a failed call, with the one-line message the command line prints";
  // Every exception from the core becomes pathlab.Error with its message, argument names as Python's.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (a failed conversion is its TypeError or RuntimeError)
    } catch (const Error& e) {
      error(e.what());
    } catch (const std::invalid_argument& e) {
      error(withArgumentNames(e.what()).c_str());
    } catch (const std::runtime_error& e) {
      error(withArgumentNames(e.what()).c_str());
    }
  });

  py::class_<TechniqueSet>(m, "TechniqueSet",
                           "A set of sampling techniques: connections (s,t), merges M(s,t) and equiangular "
                           "techniques E(1,t), as --techniques SPEC")
      .def(py::init([](const std::string& spec) { return TechniqueSet::parse(spec); }), py::arg("spec") = "all",
           "Parses SPEC: ';'-separated S,T | s=S | t=T | k=K | all | E1,T | MS,T | m=K | m=all")
      .def(
          "__contains__",
          [](const TechniqueSet& set, const py::object& key) {
            const bool tuple = py::isinstance<py::tuple>(key);
            const size_t n = tuple ? py::len(key) : 0;
            const std::string family = n == 3 && py::isinstance<py::str>(key[py::int_(0)])
                                           ? key[py::int_(0)].cast<std::string>()
                                           : std::string();
            const bool merge = family == "M", equiangular = family == "E";
            if (!(n == 2 || merge || equiangular))
              throw Error("TechniqueSet: a technique is (s, t), (\"M\", s, t) or (\"E\", 1, t)");
            const size_t first = merge || equiangular ? 1 : 0;
            const int s = static_cast<int>(intArgument(key[py::int_(first)], "TechniqueSet: s", 0, 1 << 20));
            const int t = static_cast<int>(intArgument(key[py::int_(first + 1)], "TechniqueSet: t", 0, 1 << 20));
            return merge         ? set.contains(Technique::merge(s, t))
                   : equiangular ? set.contains(Technique{s, t, TechniqueKind::Equiangular})
                                 : set.contains(s, t);
          },
          py::arg("technique"))
      .def("__str__", &TechniqueSet::toString)
      .def("__repr__", [](const TechniqueSet& s) { return fmt::format("pathlab.TechniqueSet('{}')", s.toString()); })
      .def(
          "__eq__", [](const TechniqueSet& a, const TechniqueSet& b) { return a == b; }, py::is_operator())
      .def("__hash__", [](const TechniqueSet& s) { return py::hash(py::str(s.toString())); })
      .def(
          "__or__", [](const TechniqueSet& a, const TechniqueSet& b) { return a | b; }, py::is_operator());

  py::class_<LoadedScene>(m, "Scene", "A loaded glTF scene (pathlab.load)")
      .def_readonly("path", &LoadedScene::path)
      .def_property_readonly(
          "bounds", [](const LoadedScene& s) { return py::make_tuple(vec3(s.scene->bounds().center), s.scene->bounds().radius); },
          "(centre, radius) of the scene's bounding sphere")
      .def_property_readonly("lights", [](const LoadedScene& s) { return s.scene->lights().size(); }, "The number of lights")
      .def_property_readonly("triangle_count", [](const LoadedScene& s) { return s.scene->triangleCount(); })
      .def_property_readonly("camera", [](const LoadedScene& s) { return cameraOf(s.scene->cameraDesc()); },
                             "The scene's camera: camera_to_world (4 rows), yfov or orthographic, aspect_ratio, name")
      .def_property_readonly("warnings", [](const LoadedScene& s) { return s.scene->warnings(); })
      .def("__repr__", [](const LoadedScene& s) {
        return fmt::format("pathlab.Scene('{}', {} triangles, {} lights)", s.path, s.scene->triangleCount(),
                           s.scene->lights().size());
      });

  py::class_<PySettings>(m, "Settings", "The options of `pathlab render` that decide the estimate")
      .def(py::init([](const py::kwargs& kwargs) {
             PySettings s;
             s.options = settingsFromArguments(kwargs, s.words);
             return s;
           }),
           ("Keyword arguments as render's options (max_length=5 is --max-length 5): " + settingsArgumentNames())
               .c_str())
      .def_property_readonly("integrator", [](const PySettings& s) { return s.options.estimator.integrator; })
      .def_property_readonly("techniques",
                             [](const PySettings& s) { return enabledTechniques(s.options.estimator.settings); })
      .def_property_readonly("max_length", [](const PySettings& s) { return s.options.estimator.settings.maxLength; })
      .def_property_readonly("seed", [](const PySettings& s) { return s.options.estimator.settings.seed; })
      .def_property_readonly("pyramid", [](const PySettings& s) { return s.options.estimator.settings.pyramidLength; })
      .def("__repr__", &settingsRepr);

  py::class_<Renderer>(m, "Renderer", "A progressive render of a scene with one Settings")
      .def(py::init<const LoadedScene&, const PySettings&>(), py::arg("scene"), py::arg("settings"),
           py::keep_alive<1, 2>())
      .def("render", &Renderer::render, py::arg("spp") = py::none(), py::arg("time") = py::none(),
           py::arg("progress") = py::none(),
           "Renders spp more passes (or for `time` seconds; neither: 64) and returns the image of every pass so "
           "far as a float32 array (height, width, 3). progress(spp, seconds) is called after each pass. Ctrl+C "
           "raises KeyboardInterrupt after the pass in progress, and cancel() (from any thread) makes render() return "
           "then: every pass is kept. One render at a time per renderer.")
      .def("cancel", &Renderer::cancel,
           "Stops render() after the pass in progress (any thread); called while no render runs, it stops the next")
      .def("image", &Renderer::image, "The image of every pass so far, float32 (height, width, 3)")
      .def("pyramid", &pyramidOf, py::arg("max_length") = py::none(),
           "{(s, t): (weighted, unweighted)} and {('M', s, t): ...} for every technique up to max_length (the "
           "settings' pyramid=K): its MIS-weighted share of the image and its own estimate")
      .def("technique_maps", &techniqueMapsOf,
           "With Settings(technique_maps=L): 'techniques' (the keys in index order), 'dominant' {None or k: int32 "
           "(height, width) index into 'techniques', -1 no light, -2 a tie}, 'dominant_share', 'share' {key: the "
           "technique's share of the image, -1 where it is black}, 'cannot_sample' {key: the fraction of its "
           "length's image it cannot sample, -1 where black}, and with merges 'merges_share'")
      .def("variance_maps", &varianceMapsOf,
           "With Settings(variance_maps=L): 'techniques' (the keys in index order), 'variance' {key: float32 "
           "(height, width), the technique's variance of one pass's estimate of each pixel (luminance)}, "
           "'dominant' (int32 index into 'techniques' of the technique with the most variance, -1 none, -2 a tie) "
           "and 'dominant_share' (its share of the techniques' variance)")
      .def("find_outliers", &Renderer::findOutliers, py::arg("top") = 10,
           "Keeps the `top` brightest weighted contributions of the passes from the next one on (0: stops; "
           "bpt, lt, vcm, bpm, ppm), as `pathlab outliers` does; outliers() lists them")
      .def("outliers", &outliersOf,
           "The contributions find_outliers keeps, brightest first, each replayed: the entries of `pathlab "
           "outliers --json` (luminance, value, pixel, sample, technique, raster, shareOfPixel, densityRatio, "
           "bestTechnique, record)")
      .def("counters", &countersOf, "Samples, rays, discarded samples, and per technique and walk the counters of "
                                    "`render --stats`")
      .def_property_readonly("spp", &Renderer::samplesPerPixel, "Passes (samples per pixel) rendered so far")
      .def_property_readonly("seconds", &Renderer::seconds, "Time spent in those passes")
      .def_property_readonly("width", &Renderer::width)
      .def_property_readonly("height", &Renderer::height);

  // The functions after the classes, so that their signatures name pathlab.Settings, not the C++ types.
  m.def(
      "load",
      [](const py::object& path, const py::kwargs& kwargs) {
        return loadScene(loadOptionsFromArguments(pathArgument(path, "load: path"), kwargs));
      },
      py::arg("path"),
      "Loads a glTF 2.0 scene. Keyword arguments as `pathlab render`'s options: environment (a .exr/.hdr file or "
      "three numbers), environment_strength, environment_rotation, default_light, light_sampler "
      "('auto', 'power', 'bvh'), max_triangles");

  m.def("inspect", &inspect, py::arg("scene"), py::arg("settings"), py::arg("pixel"), py::arg("sample") = 0,
        "One sample of one pixel replayed: what `pathlab inspect --json` writes for the same options, as dicts and "
        "lists (every technique, its path, and the path's density and MIS weight under every technique of its "
        "length)");

  m.def("check", &check, py::arg("scene"), py::arg("settings"),
        "`pathlab check`: renders with the check's sums (spp=N passes, or for time=SECONDS, default 10 s; the image "
        "128 pixels on its longest side unless the settings give a size) and returns what `check --json` writes: "
        "'agrees', 'techniques' (a row per technique: its status, worst z-score, p-value and region), "
        "and with merges each merge's bias radius by radius. Keyword arguments as check's options: spp, time, blocks, "
        "alpha, min_hits, radius_levels. Options of render that check does not take (pyramid, technique_maps, "
        "check_mis) are refused.");

  m.def("converge", &converge, py::arg("scene"), py::arg("configs"), py::arg("time") = py::none(),
        py::arg("spp") = py::none(), py::arg("reference") = py::none(), py::arg("factor") = 1.5,
        py::arg("clock") = "wall", py::arg("mask") = py::none(),
        "`pathlab converge`: each configuration (a Settings, a list of them, or a dict {label: Settings}) rendered "
        "for `time` seconds (default 10) or `spp` passes, its error recorded at checkpoints `factor` apart. Returns "
        "{label: {'seconds', 'wall_seconds', 'cpu_seconds', 'spp', 'camera_samples', 'rays', 'two_buffer_mse', "
        "'two_buffer_relmse', and with a reference (an image array or an .exr/.pfm path) 'mse', 'rmse', 'relmse', "
        "'mape', 'bias2', 'variance': arrays, one value per checkpoint; 'image': the final image}}. clock: 'wall' or "
        "'cpu' (process CPU time); mask: an array (height, width), the error over its non-zero pixels.");
}
