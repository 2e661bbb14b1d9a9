// pathlab.Renderer's passes with the GIL released, Ctrl+C and cancel(); the images as NumPy arrays.
#include "app/python/renderer.h"

#include "app/python/analysis.h"
#include "app/python/arguments.h"
#include "core/bpt/mis_off.h"
#include "core/metrics/technique_table.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include <unistd.h>

namespace py = pybind11;

namespace pathlab::python {

namespace {

constexpr int kDefaultSpp = 64;  // as `pathlab render` without --spp or --time


}  // namespace

PassThread::PassThread() : owner_(getpid()), thread_([this] {
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

py::array_t<float> toArray(Image image) {
  return ownedArray(std::move(image.rgb), {image.height, image.width, 3});
}

void warnAbout(const Scene& scene, const RenderSettings& settings) {
  std::vector<std::string> lines;
  if (settings.integrator != IntegratorKind::Pt)
    for (int k : enabledTechniques(settings).uncoveredLengths(settings.maxLength))
      lines.push_back(fmt::format("no enabled technique samples paths of length {}", k));
  if (std::string w = misOffWarning(scene, settings); !w.empty()) lines.push_back(std::move(w));
  if (std::string w = mediumSamplingWarning(scene, settings); !w.empty()) lines.push_back(std::move(w));
  if (std::string w = optimalMisWarning(scene, settings); !w.empty()) lines.push_back(std::move(w));
  if (std::string w = app::biasInjectionWarning(settings); !w.empty()) lines.push_back(std::move(w));
  for (const std::string& line : lines)
    if (PyErr_WarnEx(PyExc_UserWarning, withArgumentNames(line).c_str(), 2) != 0) throw py::error_already_set();
}

Renderer::Renderer(const LoadedScene& scene, const PySettings& settings) : scene_(scene), options_(settings.options) {
  try {
    app::sizeRenderForScene(options_, scene_.scene->cameraDesc());
    session_ = std::make_unique<RenderSession>(*scene_.scene, options_.estimator.settings);
  } catch (const std::exception& e) {
    throw Error(withArgumentNames(e.what()));
  }
  warnAbout(*scene_.scene, session_->settings());
}

void Renderer::findOutliers(const py::object& top) {
  const int count = static_cast<int>(intArgument(top, "find_outliers: top", 0, 1000));
  if (rendering_.load()) throw Error("find_outliers: a render is running; call it before render() or after it returns");
  try {
    session_->setOutlierCount(count);
  } catch (const std::exception& e) {
    throw Error(fmt::format("find_outliers: {}", e.what()));
  }
}

const RenderSession& Renderer::session(const char* what) const {
  if (passRunning_.load())
    throw Error(fmt::format("{}: a pass is being rendered; ask between passes (in the progress callback) or after "
                            "render() returns",
                            what));
  return *session_;
}

py::array_t<float> Renderer::render(const py::object& sppArgument, std::optional<double> seconds,
                                    const py::object& progress) {
  std::optional<int> spp;
  if (!sppArgument.is_none()) spp = static_cast<int>(intArgument(sppArgument, "render: spp", 1, app::kMaxSpp));
  if (spp && seconds) throw Error("render: give spp or time, not both");
  if (seconds && !(std::isfinite(*seconds) && *seconds > 0.0))
    throw Error(fmt::format("render: time {} is not a positive number of seconds", *seconds));
  if (!progress.is_none() && !PyCallable_Check(progress.ptr())) throw Error("render: progress must be callable");
  if (rendering_.exchange(true)) throw Error("render: this renderer is already rendering (one render at a time)");
  // Whatever ends the call: the next render starts anew; a cancel() from now on stops that one.
  struct Done {
    Renderer& r;
    ~Done() {
      r.stop_.store(false);
      r.rendering_.store(false);
    }
  } done{*this};
  const uint64_t target = spp ? static_cast<uint64_t>(*spp) : static_cast<uint64_t>(kDefaultSpp);
  const app::ThreadLimit threads(options_.threads);
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  // A renderer carried into a child by os.fork() has no pass thread there: a new one (the old
  // object is left alone, its thread belongs to the parent).
  if (passThread_ && passThread_->owner() != getpid()) (void)passThread_.release();
  if (!passThread_) passThread_ = std::make_unique<PassThread>();
  for (uint64_t passes = 0; seconds ? (passes == 0 || elapsed() < *seconds) : passes < target; ++passes) {
    if (stop_.load()) break;
    // Ctrl+C between passes.
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    // The pass on the renderer's pass thread, whole even after Ctrl+C (a pass adds its samples
    // into the film in place: one cut short could not be kept), then KeyboardInterrupt.
    std::atomic<bool> interruptedFlag{false};
    const auto passStart = std::chrono::steady_clock::now();
    passRunning_.store(true);
    bool interrupted = false;
    try {
      interrupted = runWatchingForCtrlC(*passThread_, [&] { session_->renderPass(); }, interruptedFlag);
    } catch (...) {
      passRunning_.store(false);
      throw;
    }
    passRunning_.store(false);
    seconds_.store(seconds_.load() + std::chrono::duration<double>(std::chrono::steady_clock::now() - passStart).count());
    if (interrupted) throw py::error_already_set();
    if (!progress.is_none()) progress(session_->passes(), seconds_.load());
  }
  return image();
}

py::dict pyramidOf(const Renderer& r, const py::object& maxLengthArgument) {
  const RenderSettings& s = r.settings();
  const RenderSession& session = r.session("pyramid");
  if (!session.hasPyramid())
    throw Error("pyramid: the renderer keeps no technique images (Settings(pyramid=K) keeps those up to length K)");
  const int length = maxLengthArgument.is_none()
                         ? s.pyramidLength
                         : static_cast<int>(intArgument(maxLengthArgument, "pyramid: max_length", 1, s.pyramidLength));
  py::dict out;
  for (const Technique x : TechniqueRange(1, length, session.pyramidFamilies()))
    out[techniqueKey(x)] = py::make_tuple(toArray(session.techniqueImage(x, false)),
                                          toArray(session.techniqueImage(x, true)));
  return out;
}

py::dict countersOf(const Renderer& r) {
  const Counters& c = r.session("counters").counters();
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
    else techniques[techniqueKey(Technique{row.s, row.t, row.kind})] = d;
  }
  out["techniques"] = techniques;
  out["walks"] = walks;
  return out;
}

}  // namespace pathlab::python
