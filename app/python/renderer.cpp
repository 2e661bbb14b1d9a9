// pathlab.Renderer's passes with the GIL released, Ctrl+C and cancel(); the images as NumPy arrays.
#include "app/python/renderer.h"

#include "app/python/analysis.h"
#include "app/python/arguments.h"
#include "core/metrics/technique_table.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace py = pybind11;

namespace pathlab::python {

namespace {

constexpr int kDefaultSpp = 64;  // as `pathlab render` without --spp or --time

// The film's readout held by the array (no copy); freed with it.
py::array_t<float> imageArray(std::vector<float>&& rgb, int width, int height) {
  auto* owned = new std::vector<float>(std::move(rgb));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<float>*>(p); });
  const auto w = static_cast<py::ssize_t>(width), h = static_cast<py::ssize_t>(height);
  return py::array_t<float>({h, w, py::ssize_t{3}},
                            {w * 3 * py::ssize_t{sizeof(float)}, 3 * py::ssize_t{sizeof(float)}, py::ssize_t{sizeof(float)}},
                            owned->data(), free);
}

}  // namespace

PassThread::PassThread() : thread_([this] {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return quit_ || (busy_ && job_); });
    if (quit_) return;
    std::function<void()> job = std::move(job_);
    job_ = nullptr;
    lock.unlock();
    job();
    lock.lock();
    busy_ = false;
    changed_.notify_all();
  }
}) {}

PassThread::~PassThread() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

void PassThread::start(std::function<void()> job) {
  std::lock_guard<std::mutex> lock(mutex_);
  job_ = std::move(job);
  busy_ = true;
  changed_.notify_all();
}

bool PassThread::waitFor(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [this] { return !busy_; });
}

bool runWatchingForCtrlC(PassThread& thread, const std::function<void()>& job, std::atomic<bool>& stop) {
  bool interrupted = false;
  std::exception_ptr failure;
  {
    py::gil_scoped_release release;
    thread.start([&] {
      try {
        job();
      } catch (...) {
        failure = std::current_exception();
      }
    });
    while (!thread.waitFor(std::chrono::milliseconds(20))) {
      if (interrupted) continue;  // stopping: waiting for the job to end
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {  // the exception stays set for the caller
        interrupted = true;
        stop.store(true);
      }
    }
  }
  if (interrupted) return true;
  if (failure) std::rethrow_exception(failure);
  return false;
}

LoadedScene loadScene(const app::SceneOptions& options) {
  app::SceneOptions o = options;
  try {
    return LoadedScene{o.path, std::make_shared<const Scene>(app::readScene(o))};
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
}

py::array_t<float> toArray(Image image) { return imageArray(std::move(image.rgb), image.width, image.height); }

Renderer::Renderer(const LoadedScene& scene, const PySettings& settings) : scene_(scene), options_(settings.options) {
  try {
    app::sizeRenderForScene(options_, scene_.scene->cameraDesc());
    session_ = std::make_unique<RenderSession>(*scene_.scene, options_.estimator.settings);
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
}

void Renderer::restart() {
  session_ = std::make_unique<RenderSession>(*scene_.scene, options_.estimator.settings);
  seconds_ = 0.0;
}

py::array_t<float> Renderer::render(std::optional<int> spp, std::optional<double> seconds, const py::object& progress) {
  if (spp && seconds) throw Error("render: give spp or time, not both");
  if (spp && (*spp < 1 || *spp > app::kMaxSpp))
    throw Error(fmt::format("render: spp {} is outside 1..{}", *spp, app::kMaxSpp));
  if (seconds && !(std::isfinite(*seconds) && *seconds > 0.0))
    throw Error(fmt::format("render: time {} is not a positive number of seconds", *seconds));
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw Error("render: progress must be callable");
  const uint64_t target = spp ? static_cast<uint64_t>(*spp) : static_cast<uint64_t>(kDefaultSpp);
  const app::ThreadLimit threads(options_.threads);
  stop_.store(false);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  for (uint64_t done = 0; seconds ? (done == 0 || elapsed() < *seconds) : done < target; ++done) {
    if (stop_.load()) break;
    // Ctrl+C between passes: every pass so far is kept.
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    // The pass on the renderer's pass thread, while this one (the caller's, with the GIL now and
    // then) looks for a signal every 20 ms: Python runs its Ctrl+C handler only on the main
    // thread, between bytecodes, which never come while C++ renders.
    std::atomic<bool> cancel{false};
    const auto passStart = std::chrono::steady_clock::now();
    if (!passThread_) passThread_ = std::make_unique<PassThread>();
    const bool interrupted = runWatchingForCtrlC(*passThread_, [&] { session_->renderPass(&cancel); }, cancel);
    if (interrupted) {
      restart();  // the film holds part of a pass
      throw py::error_already_set();
    }
    seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - passStart).count();
    if (!progress.is_none()) progress(session_->passes(), seconds_);
  }
  return image();
}

py::dict pyramidOf(const Renderer& r, std::optional<int> maxLength) {
  const RenderSettings& s = r.settings();
  if (!r.session().hasPyramid())
    throw Error("pyramid: the renderer keeps no technique images (Settings(pyramid=K) keeps those up to length K)");
  const int length = maxLength.value_or(s.pyramidLength);
  if (length < 1 || length > s.pyramidLength)
    throw Error(fmt::format("pyramid: max_length {} is outside 1..{} (the settings' pyramid)", length, s.pyramidLength));
  py::dict out;
  for (const Technique x : TechniqueRange(1, length, pyramidFamilies(s)))
    out[techniqueKey(x)] = py::make_tuple(toArray(r.session().techniqueImage(x, false)),
                                          toArray(r.session().techniqueImage(x, true)));
  return out;
}

py::dict countersOf(const Renderer& r) {
  const Counters& c = r.session().counters();
  py::dict out;
  out["spp"] = r.samplesPerPixel();
  out["seconds"] = r.seconds();
  out["camera_samples"] = c.cameraSamples;
  out["rays"] = c.rays;
  out["shadow_rays"] = c.shadowRays;
  const DiscardCounts d = c.discardedCounts();
  py::dict discarded;
  discarded["nan"] = d.nan;
  discarded["inf"] = d.inf;
  discarded["negative"] = d.negative;
  out["discarded"] = discarded;
  // The rows of `render --stats` and the viewer's table: each walk by name, each technique by key.
  py::dict techniques, walks;
  for (const TechniqueRow& row : techniqueRows(c, r.settings().maxLength, r.seconds())) {
    py::dict d;
    d["tried"] = row.tried;
    d["zero"] = row.zero;
    d["blocked"] = row.blocked;
    d["contributed"] = row.contributed;
    d["discarded"] = row.discarded;
    d["rays"] = row.rays;
    if (row.walk || row.s < 0) walks[py::str(row.name)] = d;
    else techniques[techniqueKey(row.kind == TechniqueKind::Merge ? Technique::merge(row.s, row.t) : Technique{row.s, row.t})] = d;
  }
  out["techniques"] = techniques;
  out["walks"] = walks;
  return out;
}

}  // namespace pathlab::python
