// pathlab.Scene and pathlab.Renderer: a loaded scene, and a progressive render of it with one
// Settings (a RenderSession, as `pathlab render` runs it, pass after pass).
#pragma once

#include "app/render_command.h"
#include "core/render/render_session.h"
#include "core/scene/scene.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <sys/types.h>

namespace pathlab::python {

struct LoadedScene {
  std::string path;
  std::shared_ptr<const Scene> scene;
};
LoadedScene loadScene(const app::SceneOptions& options);

// The render's settings: render's options (app::RenderOptions), as Settings(**kwargs) parsed them.
struct PySettings {
  app::RenderOptions options;
  std::vector<std::string> words;  // the options as command-line words (pathlab.check parses them again)
};

// `values` as a C-ordered array of `shape` that owns them (moved in, not copied; freed with it).
template <class T>
pybind11::array_t<T> ownedArray(std::vector<T>&& values, std::initializer_list<int> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  pybind11::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  std::vector<pybind11::ssize_t> dims(shape.begin(), shape.end());
  return pybind11::array_t<T>(dims, owned->data(), free);
}

// An image as a float32 H x W x 3 array that owns its pixels: the film's readout is moved into
// it, not copied.
pybind11::array_t<float> toArray(Image image);

// One thread that runs a renderer's passes, kept from pass to pass: a thread started for every
// pass, and its first TBB work, cost a 64 x 64 pass several per cent (docs/benchmarks.md).
class PassThread {
 public:
  PassThread();
  ~PassThread();
  PassThread(const PassThread&) = delete;
  PassThread& operator=(const PassThread&) = delete;
  // Runs `job` on the thread; waitFor then returns true once it has finished.
  void start(std::function<void()> job);
  bool waitFor(std::chrono::milliseconds timeout);
  // The process that started the thread: after os.fork() the child has no such thread.
  pid_t owner() const { return owner_; }

 private:
  pid_t owner_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::function<void()> job_;
  bool busy_ = false, quit_ = false;
  std::thread thread_;  // last: started once the members it reads exist
};

// Runs `job` on a PassThread with the GIL released while the calling thread looks for Ctrl+C every
// 20 ms (Python runs its signal handlers only on the main thread, between bytecodes, which never
// come while C++ works). On Ctrl+C `stop` is set and the job is waited for; returns true then,
// with KeyboardInterrupt set for the caller to raise (py::error_already_set). An exception of the
// job is rethrown.
bool runWatchingForCtrlC(PassThread& thread, const std::function<void()>& job, std::atomic<bool>& stop);

class Renderer {
 public:
  Renderer(const LoadedScene& scene, const PySettings& settings);

  // Renders `spp` more passes, or passes for `seconds` of wall time (at least one); neither: 64
  // passes, as `pathlab render`. Returns the image of every pass so far. The GIL is released
  // while the passes run; `progress(spp, seconds)` is called after each pass. Ctrl+C (a signal
  // Python sees on its main thread) and cancel() (any thread) stop after the pass in progress,
  // every pass kept: Ctrl+C then raises KeyboardInterrupt, cancel() makes render() return. A
  // cancel() while no render runs stops the next one at once. One render at a time per renderer.
  pybind11::array_t<float> render(const pybind11::object& spp, std::optional<double> seconds,
                                  const pybind11::object& progress);
  void cancel() { stop_.store(true); }

  pybind11::array_t<float> image() const { return toArray(session("image").image()); }
  uint64_t samplesPerPixel() const { return session_->passes(); }
  double seconds() const { return seconds_.load(); }
  const RenderSettings& settings() const { return session_->settings(); }
  // The session between passes (from the progress callback, or when no render runs); refused
  // with an Error naming `what` while a pass writes it.
  const RenderSession& session(const char* what) const;
  int width() const { return settings().width; }
  int techniqueMapLength() const { return options_.techniqueMaps; }
  int varianceMapLength() const { return options_.varianceMaps; }
  // The outlier finder (RenderSession::setOutlierCount) from the next pass on: refused while a pass
  // runs, and for settings without independent bidirectional samples.
  void findOutliers(const pybind11::object& top);
  int height() const { return settings().height; }

 private:
  LoadedScene scene_;
  app::RenderOptions options_;
  std::unique_ptr<RenderSession> session_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> rendering_{false};   // a render() call is running
  std::atomic<bool> passRunning_{false};  // ... and its pass thread is writing the session
  std::atomic<double> seconds_{0.0};  // rendering time of the passes held
  std::unique_ptr<PassThread> passThread_;  // made by the first render
};

// The estimator's warnings for these settings on this scene (a technique-less length, MIS off's
// bias, an injected bias), as Python UserWarnings.
void warnAbout(const Scene& scene, const RenderSettings& settings);

// {(s, t): (weighted, unweighted)} and {("M", s, t): ...} up to `maxLength` (the settings'
// pyramid length when not given).
pybind11::dict pyramidOf(const Renderer& r, const pybind11::object& maxLength);
// The counters of every pass so far: samples, rays, discarded samples, per technique and walk.
pybind11::dict countersOf(const Renderer& r);

}  // namespace pathlab::python
