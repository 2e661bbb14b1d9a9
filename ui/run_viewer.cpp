// The viewer's frame loop over a Surface: ImGui frame, viewer, image pass, ImGui draw data,
// present; frame pacing, frame-time statistics, screenshots.
#include "ui/run_viewer.h"

#include "ui/egl_surface.h"
#include "ui/gl.h"
#include "ui/glfw_surface.h"
#include "ui/input_script.h"
#include "ui/output_names.h"
#include "ui/presets/preset_controller.h"
#include "ui/recorder.h"
#include "ui/scene_loader.h"
#include "ui/screenshot.h"
#include "ui/viewer.h"

#include <fmt/core.h>
#include <imgui.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <numeric>
#include <stdexcept>
#include <thread>

namespace pathlab::ui {

namespace {

using Clock = std::chrono::steady_clock;

// 60 Hz: enough for smooth orbiting; the rest of the CPU goes to the render threads.
constexpr double kFrameSeconds = 1.0 / 60.0;
// After input, frames are drawn for this long even without further events (hover, animations).
constexpr double kInputLingerSeconds = 0.5;
// Longest sleep in the event wait of an idle window (bounds the latency of a new image).
constexpr double kIdleWaitSeconds = 0.05;
// How long a headless screenshot waits for --spp before giving up (and saying so).
constexpr double kHeadlessSppTimeout = 300.0;

// ImGui owns one context per process; this keeps its lifetime tied to the viewer's.
struct ImGuiContextScope {
  ImGuiContextScope() { ImGui::CreateContext(); }
  ~ImGuiContextScope() { ImGui::DestroyContext(); }
};

struct OpenGl3Backend {
  OpenGl3Backend() {
    if (!ImGui_ImplOpenGL3_Init("#version 330 core")) throw std::runtime_error("Dear ImGui: OpenGL 3 backend failed");
  }
  ~OpenGl3Backend() { ImGui_ImplOpenGL3_Shutdown(); }
};

void setUpFontsAndStyle(float scale) {
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;  // no imgui.ini next to wherever the viewer was started
  ImGui::StyleColorsDark();
  ImGuiStyle& style = ImGui::GetStyle();
  style.WindowRounding = 4.f;
  style.FrameRounding = 3.f;
  style.ScaleAllSizes(scale);
  // A real font file scales cleanly for a projector; the built-in bitmap font otherwise.
  const char* font = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
  if (std::filesystem::exists(font)) {
    io.Fonts->AddFontFromFileTTF(font, 15.f * scale);
  } else {
    ImFontConfig config;
    config.SizePixels = 13.f * scale;
    io.Fonts->AddFontDefault(&config);
  }
}

// Lecture mode's UI scale: text as tall relative to the window at every projector resolution —
// 2 at 1080 lines (a 30 px font), 1.33 at 720 (20 px), so that at 1280 x 720 the side panel keeps
// to 40 % of the width and the image gets the rest; never below 1.25 nor above 3.
float lectureScale(int windowHeight) { return std::clamp(static_cast<float>(windowHeight) / 540.f, 1.25f, 3.f); }

void checkErrorCsvPath(const ViewerOptions& o) {
  const std::filesystem::path path(o.errorCsv);
  if (!path.parent_path().empty() && !std::filesystem::is_directory(path.parent_path()))
    throw std::runtime_error(o.errorCsv + ": the directory " + path.parent_path().string() + " does not exist");
  if (!o.force && std::filesystem::exists(path))
    throw std::runtime_error(o.errorCsv + ": file exists (pass --force to overwrite it)");
}

void checkScreenshotPath(const ViewerOptions& o) {
  const std::filesystem::path path(o.screenshot);
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".png") throw std::runtime_error(o.screenshot + ": a screenshot is a .png");
  if (!path.parent_path().empty() && !std::filesystem::is_directory(path.parent_path()))
    throw std::runtime_error(o.screenshot + ": the directory " + path.parent_path().string() + " does not exist");
  if (!o.force && std::filesystem::exists(path))
    throw std::runtime_error(o.screenshot + ": file exists (pass --force to overwrite it)");
}

struct FrameStats {
  std::vector<double> ms;
  void add(double v) { ms.push_back(v); }
  std::string summary() const {
    // The first frames build the font atlas and compile shaders: leave them out.
    if (ms.size() < 4) return "too few frames to measure";
    std::vector<double> v(ms.begin() + 2, ms.end());
    std::sort(v.begin(), v.end());
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
    return fmt::format("{} frames, UI frame time mean {:.1f} ms, median {:.1f} ms, 95% {:.1f} ms, max {:.1f} ms",
                       ms.size(), mean, v[v.size() / 2], v[std::min(v.size() - 1, v.size() * 95 / 100)], v.back());
  }
};

void saveScreenshot(const std::string& path, Vec2i size) { writePngRgba(path, size, readFramebufferRgba(size)); }

// The recorder and its take's clock. Headless, every drawn frame advances the clock by the UI
// frame period (a simulated clock: the same script writes the same frames on any machine); in a
// window it is the wall clock, so the clip plays at the speed the lecture happened.
struct Recording {
  std::unique_ptr<Recorder> recorder;
  bool headless = false, imageOnly = false;
  int fps = 30;
  long long takeFrames = 0;  // frames drawn in this take
  Clock::time_point takeStart{};

  bool active() const { return recorder && recorder->recording(); }
  void start(Viewer& viewer, const std::string& dir) {
    if (!recorder) recorder = std::make_unique<Recorder>(dir, fps, headless);
    recorder->start();
    takeFrames = 0;
    takeStart = Clock::now();
    viewer.setRecording(true);
    std::cerr << fmt::format("pathlab view: recording into {} at {} fps\n", recorder->dir(), fps);
  }
  void toggle(Viewer& viewer) {
    if (active()) {
      recorder->stop();
      viewer.setRecording(false);
      return;
    }
    try {
      // Without --record, each recording gets a fresh directory beside the screenshots.
      std::string dir = recorder ? recorder->dir() : freshStem("out", "pathlab-recording", {""});
      if (!recorder) prepareRecordDirectory(dir, false);
      start(viewer, dir);
    } catch (const std::exception& e) {
      viewer.showMessage(e.what(), true);
    }
  }
  // After the frame is drawn, before it is presented.
  void capture(const Viewer& viewer, Vec2i fb) {
    if (!active()) return;
    const double t = headless ? static_cast<double>(takeFrames) * kFrameSeconds
                              : std::chrono::duration<double>(Clock::now() - takeStart).count();
    ++takeFrames;
    const int copies = recorder->framesDue(t);
    if (copies == 0) return;
    // The image area includes the caption drawn over it (ImGui's foreground list is drawn by now).
    const Vec2i origin = imageOnly ? viewer.imageOrigin() : Vec2i(0);
    const Vec2i size = imageOnly ? viewer.imageSize() : fb;
    if (size.x <= 0 || size.y <= 0) return;
    recorder->submit(readFramebufferRgba(fb, origin, size), size, copies);
  }
  void report(Viewer* viewer) {
    if (!recorder) return;
    while (const std::optional<std::string> r = recorder->takeReport()) {
      std::cerr << "pathlab view: " << *r << "\n";
      if (viewer) viewer->showMessage(*r, r->starts_with("warning"));
    }
  }
};

// Feeds this frame's scripted input to ImGui (after the platform backend's own, so it wins).
// Returns the files the script drops on the window in this frame.
std::vector<std::string> applyScript(const std::vector<InputEvent>& script, int frame, std::vector<int>& held) {
  if (script.empty()) return {};
  ImGuiIO& io = ImGui::GetIO();
  for (int key : held) io.KeysDown[key] = false;
  const FrameInput in = inputAt(script, frame);
  held = in.keysDown;
  for (int key : held) io.KeysDown[key] = true;
  io.KeyCtrl = in.ctrl;
  io.KeyShift = in.shift;
  if (in.hasMouse) {
    io.MousePos = ImVec2(in.mouse.x, in.mouse.y);
    io.MouseDown[0] = in.mouseDown;
  }
  return in.dropped;
}

// Headless (FRAME:wait=SPP, the last frame): waits for the scene being loaded, then until every
// side shows `spp` samples per pixel.
void waitForSpp(Viewer& viewer, uint64_t spp) {
  viewer.finishLoading(kHeadlessSppTimeout);
  for (RenderLane* lane : {&viewer.a(), &viewer.b()})
    if (lane->running() && !lane->renderer().waitForSpp(spp, kHeadlessSppTimeout))
      std::cerr << fmt::format("pathlab: warning: {}{} spp not reached within {:.0f} s\n",
                               lane == &viewer.b() ? "side B: " : "", spp, kHeadlessSppTimeout);
}

}  // namespace

int runViewer(const ViewerOptions& o) {
  if (o.headless && o.screenshot.empty() && o.recordDir.empty())
    throw std::runtime_error("--headless needs --screenshot OUT.png or --record DIR");
  if (!o.screenshot.empty()) checkScreenshotPath(o);
  if (!o.errorCsv.empty()) checkErrorCsvPath(o);
  if ((!o.errorCsv.empty() || o.errorView) && o.reference.empty())
    throw std::runtime_error(std::string(o.errorView ? "--error-view" : "--error-csv") + " needs --reference REF.exr");
  ViewerOptions options = o;
  std::vector<NamedPreset> presets = loadPresetsOf(options);
  const std::vector<InputEvent> script = parseInputScript(o.script);
  if (!o.recordDir.empty()) prepareRecordDirectory(o.recordDir, o.force);  // refused before the scene loads
  std::vector<int> scriptKeys;
  SceneLoadResult loaded = SceneLoader::load(o.scene, o.load);
  if (!loaded.scene) throw std::runtime_error(loaded.error);
  for (const std::string& w : loaded.scene->warnings()) std::cerr << "pathlab: warning: " << w << "\n";

  ImGuiContextScope imgui;
  std::unique_ptr<Surface> surface;
  if (o.headless) surface = std::make_unique<EglSurface>(o.windowWidth, o.windowHeight);
  else surface = std::make_unique<GlfwSurface>(o.windowWidth, o.windowHeight, "pathlab view " + o.scene);
  const float uiScale = (o.lecture ? lectureScale(surface->framebufferSize().y / std::max(surface->contentScale(), 1.f)) : 1.f) *
                        surface->contentScale();
  setUpFontsAndStyle(uiScale);
  OpenGl3Backend backend;
  FrameStats stats;
  int exitCode = 0;
  {
    Viewer viewer(options, loaded.scene, std::move(presets));
    viewer.setUiScale(uiScale);
    Recording recording;
    recording.headless = o.headless;
    recording.imageOnly = o.recordImage;
    recording.fps = o.recordFps;
    if (!o.recordDir.empty()) recording.start(viewer, o.recordDir);
    auto lastInput = Clock::now();
    int frame = 0;
    const bool counted = o.frames > 0;  // draw every frame and stop after o.frames
    while (counted ? frame < o.frames && !surface->shouldClose() : !surface->shouldClose() && !viewer.quitRequested()) {
      const bool last = counted && frame == o.frames - 1;
      if (last && o.spp > 0) {
        // The screenshot shows the requested sample count (settings were applied in earlier frames).
        waitForSpp(viewer, o.spp);
        viewer.waitForPyramid(5.0);
      }
      if (const std::optional<uint64_t> spp = inputAt(script, frame).waitSpp) {
        waitForSpp(viewer, *spp);
        viewer.forceRefresh();
      }
      if (last) viewer.forceRefresh();
      // A window draws only after input (for a moment, so ImGui can settle hover states) and when
      // a new image arrives; otherwise it sleeps in the event wait and the CPU renders.
      const bool recent = std::chrono::duration<double>(Clock::now() - lastInput).count() < kInputLingerSeconds;
      // While recording every frame is drawn: the clip needs frames when nothing changes too.
      const bool recordingNow = recording.active();
      if (surface->waitEvents(recent || counted || recordingNow ? 0.0 : kIdleWaitSeconds)) lastInput = Clock::now();
      const auto start = Clock::now();
      const bool newImage = viewer.pollImage();
      const bool active = std::chrono::duration<double>(start - lastInput).count() < kInputLingerSeconds;
      recording.report(&viewer);
      if (!counted && !active && !newImage && !viewer.busy() && !recordingNow) continue;
      ++frame;
      // A scripted resize first: the platform frame then sees the new size.
      if (const auto size = inputAt(script, frame - 1).resize) surface->resize(*size);
      surface->newFrame();
      std::vector<std::string> dropped = surface->takeDroppedPaths();
      for (std::string& path : applyScript(script, frame - 1, scriptKeys)) dropped.push_back(std::move(path));
      ImGui_ImplOpenGL3_NewFrame();
      ImGui::NewFrame();
      const ImGuiIO& io = ImGui::GetIO();
      const Vec2i fb = surface->framebufferSize();
      const float fbScale = io.DisplaySize.x > 0.f ? static_cast<float>(fb.x) / io.DisplaySize.x : 1.f;
      viewer.setFrameTime(stats.ms.empty() ? 0.0 : stats.ms.back());
      if (const EnvironmentEdit edit = inputAt(script, frame - 1).environment; !edit.empty()) viewer.editEnvironment(edit);
      viewer.buildFrame(fb, fbScale, dropped);
      ImGui::Render();
      glViewport(0, 0, fb.x, fb.y);
      glClearColor(0.08f, 0.08f, 0.09f, 1.f);
      glClear(GL_COLOR_BUFFER_BIT);
      viewer.drawImage(fb);
      glViewport(0, 0, fb.x, fb.y);
      ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
      if (viewer.takeScreenshotRequest()) {
        try {
          const std::string path = freshStem("out", "pathlab-screenshot", {".png"}) + ".png";
          saveScreenshot(path, fb);
          viewer.showMessage("screenshot " + path);
        } catch (const std::exception& e) {
          viewer.showMessage(e.what(), true);
        }
      }
      if (const std::optional<PixelRect> rect = viewer.takeView3DExportRequest()) {
        try {
          const std::string path = freshStem("out", "pathlab-3d", {".png"}) + ".png";
          writePngRgba(path, rect->size, readFramebufferRgba(fb, rect->origin, rect->size));
          viewer.showMessage("3D view " + path);
        } catch (const std::exception& e) {
          viewer.showMessage(e.what(), true);
        }
      }
      if (viewer.takeRecordingToggleRequest()) recording.toggle(viewer);
      recording.capture(viewer, fb);
      if (last && !o.screenshot.empty()) {
        glFinish();
        saveScreenshot(o.screenshot, fb);
      }
      surface->present();
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
      if (!last) stats.add(ms);
      // Bounded frame rate (vsync may be missing, e.g. under Xvfb or offscreen).
      const double rest = kFrameSeconds - ms / 1000.0;
      if (rest > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(rest));
    }
    if (counted) {
      const RenderSnapshot& s = viewer.a().snapshot();
      const Vec2i fb = surface->framebufferSize();
      const std::string series =
          o.reference.empty() ? std::string() : fmt::format("; {} error series", viewer.errors().series().size());
      // The region the last frame drew (what the screenshot shows), then the resolution rendered:
      // they differ under --render-scale or a reference's size, and on a busy machine the shown
      // snapshot may still be a placeholder generation's.
      const PixelRect drawn = viewer.a().drawn();
      std::string compare;
      if (viewer.b().running()) {
        const PixelRect b = viewer.b().drawn();
        compare = fmt::format(", B image {}x{}+{}+{} at {} spp", b.size.x, b.size.y, b.origin.x, b.origin.y,
                              viewer.b().snapshot().samplesPerPixel);
      }
      if (const std::optional<PixelRect> v = viewer.drawnView3D())
        compare += fmt::format(", 3D view {}x{}+{}+{}", v->size.x, v->size.y, v->origin.x, v->origin.y);
      // The generation: how often the render restarted (a test's proof that something did not).
      // How next-event estimation chooses lights in the scene shown (a relight may have changed it).
      const char* nee = viewer.shownScene().lights().neeByContext() ? "bvh" : "power";
      std::cerr << fmt::format(
          "{}: {}x{} {}, image {}x{}+{}+{} at {} spp{}, rendered {}x{} (generation {}), next-event lights {}; {}{}\n",
          o.screenshot.empty() ? "pathlab view" : o.screenshot, fb.x, fb.y, o.headless ? "offscreen" : "window",
          drawn.size.x, drawn.size.y, drawn.origin.x, drawn.origin.y, s.samplesPerPixel, compare, s.settings.width,
          s.settings.height, s.generation, nee, stats.summary(), series);
      // Offscreen nobody reads the panel: its error line goes to standard error too.
      if (const std::string error = viewer.shownError(); !error.empty())
        std::cerr << "pathlab view: shown: " << error << "\n";
    }
    if (!o.errorCsv.empty()) viewer.writeErrorCsv(o.errorCsv, true);  // checked before the first frame
    if (recording.recorder) {
      recording.recorder->finish();  // the last frames written, the clip assembled
      recording.report(nullptr);
    }
  }  // the viewer (and its render threads) goes before the GL context
  return exitCode;
}

}  // namespace pathlab::ui
