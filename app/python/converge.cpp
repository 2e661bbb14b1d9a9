// pathlab.converge: runConvergence per configuration, on a thread of its own while the caller
// watches for Ctrl+C.
#include "app/python/converge.h"

#include "app/python/analysis.h"
#include "app/python/arguments.h"
#include "core/converge/convergence.h"
#include "core/image/image_read.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <fmt/core.h>

#include <cmath>
#include <exception>
#include <vector>

namespace py = pybind11;

namespace pathlab::python {

namespace {

constexpr double kDefaultSeconds = 10.0;  // per configuration, as `pathlab converge`

// "integrator=pt max_length=5" from the words ["--integrator", "pt", "--max-length", "5"]; "bpt"
// when none were given.
std::string labelOf(const std::vector<std::string>& words) {
  std::string label;
  for (size_t i = 0; i < words.size(); ++i) {
    const bool option = words[i].starts_with("--");
    const std::string word = option ? withArgumentNames(words[i]) : words[i];
    label += option ? (label.empty() ? "" : " ") + word : "=" + word;
  }
  return label.empty() ? "bpt" : label;
}

Image imageFrom(const py::object& value) {
  if (py::isinstance<py::str>(value) || py::hasattr(value, "__fspath__"))
    return readImage(pathArgument(value, "converge: reference"));
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 3 || a.shape(2) != 3) throw Error("converge: reference must be a path or an array (height, width, 3)");
  Image image{static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)), {}};
  image.rgb.assign(a.data(), a.data() + a.size());
  for (float v : image.rgb)
    if (!std::isfinite(v)) throw Error("converge: the reference holds a NaN or infinite value");
  return image;
}

PixelMask maskFrom(const py::object& value, int width, int height) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || a.ndim() != 2 || a.shape(0) != height || a.shape(1) != width)
    throw Error(fmt::format("converge: mask must be an array ({}, {}), the images' size", height, width));
  PixelMask mask(static_cast<size_t>(a.size()));
  size_t count = 0;
  for (size_t i = 0; i < mask.size(); ++i) {
    const double v = a.data()[i];
    count += mask[i] = !std::isnan(v) && v != 0.0 ? 1 : 0;  // NaN counts as outside, as converge --mask
  }
  if (count == 0) throw Error("converge: the mask selects no pixel");
  return mask;
}

template <class T, class F>
py::array_t<T> column(const std::vector<Checkpoint>& checkpoints, F&& value) {
  py::array_t<T> out(static_cast<py::ssize_t>(checkpoints.size()));
  auto w = out.template mutable_unchecked<1>();
  for (size_t i = 0; i < checkpoints.size(); ++i) w(static_cast<py::ssize_t>(i)) = value(checkpoints[i]);
  return out;
}

py::dict curveDict(ConvergenceCurve&& curve, bool withReference) {
  const std::vector<Checkpoint>& c = curve.checkpoints;
  py::dict d;
  d["seconds"] = column<double>(c, [](const Checkpoint& p) { return p.seconds; });
  d["wall_seconds"] = column<double>(c, [](const Checkpoint& p) { return p.wallSeconds; });
  d["cpu_seconds"] = column<double>(c, [](const Checkpoint& p) { return p.cpuSeconds; });
  d["spp"] = column<uint64_t>(c, [](const Checkpoint& p) { return p.spp; });
  d["camera_samples"] = column<uint64_t>(c, [](const Checkpoint& p) { return p.cameraSamples; });
  d["rays"] = column<uint64_t>(c, [](const Checkpoint& p) { return p.rays; });
  d["two_buffer_mse"] = column<double>(c, [](const Checkpoint& p) { return p.twoBuffer.mse; });
  d["two_buffer_relmse"] = column<double>(c, [](const Checkpoint& p) { return p.twoBuffer.relMse; });
  if (withReference) {
    const double nan = std::nan("");
    d["mse"] = column<double>(c, [&](const Checkpoint& p) { return p.error ? p.error->mse : nan; });
    d["rmse"] = column<double>(c, [&](const Checkpoint& p) { return p.error ? p.error->rmse : nan; });
    d["relmse"] = column<double>(c, [&](const Checkpoint& p) { return p.error ? p.error->relMse : nan; });
    d["mape"] = column<double>(c, [&](const Checkpoint& p) { return p.error ? p.error->mape : nan; });
    d["bias2"] = column<double>(c, [&](const Checkpoint& p) { return p.split ? p.split->bias2 : nan; });
    d["variance"] = column<double>(c, [&](const Checkpoint& p) { return p.split ? p.split->variance : nan; });
  }
  d["image"] = toArray(std::move(curve.image));
  return d;
}

}  // namespace

py::dict converge(const LoadedScene& scene, const py::object& configs, std::optional<double> seconds,
                  const py::object& sppArgument, const py::object& reference, double factor, const std::string& clock,
                  const py::object& mask) {
  // The configurations and their labels.
  // Copies: a sequence may hand out objects that live only as long as the loop's step.
  std::vector<std::pair<std::string, PySettings>> given;
  if (py::isinstance<PySettings>(configs)) {
    const PySettings& s = configs.cast<const PySettings&>();
    given.emplace_back(labelOf(s.words), s);
  } else if (py::isinstance<py::dict>(configs)) {
    for (const auto& [key, value] : configs.cast<py::dict>()) {
      if (!py::isinstance<PySettings>(value)) throw Error("converge: configs must map labels to Settings");
      given.emplace_back(py::str(key).cast<std::string>(), value.cast<PySettings>());
    }
  } else if (py::isinstance<py::sequence>(configs) && !py::isinstance<py::str>(configs)) {
    for (const py::handle& value : configs.cast<py::sequence>()) {
      if (!py::isinstance<PySettings>(value)) throw Error("converge: configs must be Settings");
      const PySettings s = value.cast<PySettings>();
      given.emplace_back(labelOf(s.words), s);
    }
  } else {
    throw Error("converge: configs must be a Settings, a list of them or a dict {label: Settings}");
  }
  if (given.empty()) throw Error("converge: no configuration");
  for (size_t i = 0; i < given.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (given[i].first == given[j].first)
        throw Error(fmt::format("converge: two configurations are labelled '{}' (a dict labels them apart)", given[i].first));
  std::optional<int> spp;
  if (!sppArgument.is_none()) spp = static_cast<int>(intArgument(sppArgument, "converge: spp", 2, app::kMaxSpp));
  if (spp && seconds) throw Error("converge: give spp or time, not both");
  if (seconds && !(std::isfinite(*seconds) && *seconds > 0.0))
    throw Error(fmt::format("converge: time {} is not a positive number of seconds", *seconds));
  if (!(factor >= 1.01 && factor <= 100.0)) throw Error(fmt::format("converge: factor {} is outside 1.01..100", factor));
  if (clock != "wall" && clock != "cpu") throw Error(fmt::format("converge: clock '{}' is not wall or cpu", clock));
  ConvergenceBudget budget;
  budget.factor = factor;
  budget.clock = clock == "cpu" ? ClockKind::Cpu : ClockKind::Wall;
  if (spp) budget.spp = static_cast<uint64_t>(*spp);
  else budget.seconds = seconds.value_or(kDefaultSeconds);

  std::optional<Image> ref;
  if (!reference.is_none()) {
    try {
      ref = imageFrom(reference);
    } catch (const Error&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(e.what());
    }
  }
  std::vector<ConvergenceConfig> runs;
  std::vector<int> threads;  // each configuration's threads= (0: all)
  for (const auto& [label, settings] : given) {
    app::RenderOptions o = settings.options;
    // The reference's size unless the settings give one, as `converge --reference`.
    if (ref && o.size.width == 0 && o.size.height == 0) {
      o.size.width = ref->width;
      o.size.height = ref->height;
    }
    try {
      app::sizeRenderForScene(o, scene.scene->cameraDesc());
      validateSettingsForCamera(o.estimator.settings, scene.scene->cameraDesc());
      validateSettingsForScene(o.estimator.settings, *scene.scene);
    } catch (const std::exception& e) {
      throw Error(fmt::format("converge: '{}': {}", label, withArgumentNames(e.what())));
    }
    const RenderSettings& s = o.estimator.settings;
    if (ref && (s.width != ref->width || s.height != ref->height))
      throw Error(fmt::format("converge: '{}' renders {} x {}, the reference is {} x {}", label, s.width, s.height,
                              ref->width, ref->height));
    runs.push_back(ConvergenceConfig{label, s});
    threads.push_back(o.threads);
  }
  PixelMask pixels;
  if (!mask.is_none() && !ref) throw Error("converge: a mask selects where the error against the reference is measured: give a reference");
  if (!mask.is_none()) pixels = maskFrom(mask, runs.front().settings.width, runs.front().settings.height);
  for (const ConvergenceConfig& run : runs) warnAbout(*scene.scene, run.settings);

  py::dict out;
  for (size_t i = 0; i < runs.size(); ++i) {
    const ConvergenceConfig& run = runs[i];
    // On the pass thread, while this one looks for Ctrl+C every 20 ms (Renderer::render).
    std::atomic<bool> stop{false};
    ConvergenceCurve curve;
    PassThread thread;
    try {
      const bool interrupted = runWatchingForCtrlC(
          thread,
          [&] {
            const app::ThreadLimit limit(threads[i]);
            curve = runConvergence(*scene.scene, run, ref ? &*ref : nullptr, budget, {}, nullptr, nullptr, pixels, &stop);
          },
          stop);
      if (interrupted) throw py::error_already_set();
    } catch (const ConvergenceStopped&) {
      throw py::error_already_set();
    } catch (const py::error_already_set&) {
      throw;
    } catch (const std::exception& e) {
      throw Error(fmt::format("converge: '{}': {}", run.label, withArgumentNames(e.what())));
    }
    out[py::str(run.label)] = curveDict(std::move(curve), ref.has_value());
  }
  return out;
}

}  // namespace pathlab::python
