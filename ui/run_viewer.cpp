// `pathlab view` step by step: options checked, presets and the scene loaded, the surface opened,
// then the frame loop over it (ImGui frame, viewer, image pass, ImGui draw data, present; frame
// pacing, frame-time statistics, screenshots, recording), its report and what it writes at the end.
#include "ui/run_viewer.h"

#include "core/film/image_io.h"

#include "ui/gl/gl.h"
#include "ui/gl/screenshot.h"
#include "ui/input/input_script.h"
#include "ui/presets/preset_controller.h"
#include "ui/record/output_names.h"
#include "ui/record/recording.h"
#include "ui/record/recording_controller.h"
#include "ui/scene/scene_loader.h"
#include "ui/surface/egl_surface.h"
#include "ui/surface/glfw_surface.h"
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

// Step 1: options that cannot work together, and output paths refused before anything loads.
void checkOptions(const ViewerOptions& o) {
  if (o.headless && o.screenshot.empty() && o.recordDir.empty())
    throw std::runtime_error("--headless needs --screenshot OUT.png or --record DIR");
  if (!o.screenshot.empty()) checkScreenshotPath(o);
  if (!o.errorCsv.empty()) checkErrorCsvPath(o);
  if ((!o.errorCsv.empty() || o.errorView) && o.reference.empty())
    throw std::runtime_error(std::string(o.errorView ? "--error-view" : "--error-csv") + " needs --reference REF.exr");
}

// Step 2: the scene, before any window opens (a bad one is the command's error).
std::shared_ptr<const Scene> loadStartScene(const ViewerOptions& o) {
  SceneLoadResult loaded = SceneLoader::load(o.scene, o.load);
  if (!loaded.scene) throw std::runtime_error(loaded.error);
  for (const std::string& w : loaded.scene->warnings()) std::cerr << "pathlab: warning: " << w << "\n";
  return loaded.scene;
}

// Step 3: the window, or the headless EGL context.
std::unique_ptr<Surface> openSurface(const ViewerOptions& o) {
  if (o.headless) return std::make_unique<EglSurface>(o.windowWidth, o.windowHeight);
  return std::make_unique<GlfwSurface>(o.windowWidth, o.windowHeight, "pathlab view " + o.scene);
}

float uiScaleOf(const ViewerOptions& o, const Surface& surface) {
  const float content = surface.contentScale();
  return (o.lecture ? lectureScale(surface.framebufferSize().y / std::max(content, 1.f)) : 1.f) * content;
}

// Step 4: the frames, from the first to the window's closing (or the last counted one).
class FrameLoop {
 public:
  FrameLoop(const ViewerOptions& o, std::vector<InputEvent> script, Surface& surface, Viewer& viewer)
      : o_(o), surface_(surface), viewer_(viewer), script_(std::move(script)),
        recording_(o.headless, o.recordImage, o.recordFps, kFrameSeconds) {}

  void run() {
    if (!o_.recordDir.empty()) recording_.start(viewer_, o_.recordDir);
    while (counted() ? frame_ < o_.frames && !surface_.shouldClose() : !surface_.shouldClose() && !viewer_.quitRequested())
      step();
  }
  // Step 5: what the run showed, on stderr (counted runs: the tests' and scripts' evidence).
  void report() const;
  // Step 6: the error series and the recording written.
  void finish() {
    if (!o_.errorCsv.empty()) viewer_.writeErrorCsv(o_.errorCsv, true);  // checked before the first frame
    recording_.finish();
  }

 private:
  const ViewerOptions& o_;
  Surface& surface_;
  Viewer& viewer_;
  const std::vector<InputEvent> script_;
  std::vector<int> scriptKeys_;
  RecordingController recording_;
  FrameStats stats_;
  Clock::time_point lastInput_ = Clock::now();
  int frame_ = 0;

  bool counted() const { return o_.frames > 0; }  // draw every frame and stop after o.frames

  void step() {
    const bool last = counted() && frame_ == o_.frames - 1;
    waitForScript(last);
    // A window draws only after input (for a moment, so ImGui can settle hover states) and when
    // a new image arrives; otherwise it sleeps in the event wait and the CPU renders.
    const bool recent = std::chrono::duration<double>(Clock::now() - lastInput_).count() < kInputLingerSeconds;
    // While recording every frame is drawn: the clip needs frames when nothing changes too.
    const bool recordingNow = recording_.active();
    if (surface_.waitEvents(recent || counted() || recordingNow ? 0.0 : kIdleWaitSeconds)) lastInput_ = Clock::now();
    const auto start = Clock::now();
    const bool newImage = viewer_.pollImage();
    const bool active = std::chrono::duration<double>(start - lastInput_).count() < kInputLingerSeconds;
    recording_.report(&viewer_);
    if (!counted() && !active && !newImage && !viewer_.busy() && !recordingNow) return;
    ++frame_;
    const Vec2i fb = drawFrame();
    saveRequests(fb);
    if (last && !o_.screenshot.empty()) {
      glFinish();
      saveScreenshot(o_.screenshot, fb);
    }
    surface_.present();
    const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (!last) stats_.add(ms);
    // Bounded frame rate (vsync may be missing, e.g. under Xvfb or offscreen).
    const double rest = kFrameSeconds - ms / 1000.0;
    if (rest > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(rest));
  }

  // Headless, before the frame that shows them: the samples the last frame or a script asks for.
  void waitForScript(bool last) {
    if (last && o_.spp > 0) {
      // The screenshot shows the requested sample count (settings were applied in earlier frames).
      waitForSpp(viewer_, o_.spp);
      viewer_.waitForPyramid(5.0);
    }
    if (const std::optional<uint64_t> spp = inputAt(script_, frame_).waitSpp) {
      waitForSpp(viewer_, *spp);
      viewer_.forceRefresh();
    }
    if (last) viewer_.forceRefresh();
  }

  // The UI frame (scripted input included) built and drawn: the image, then ImGui over it.
  Vec2i drawFrame() {
    // A scripted resize first: the platform frame then sees the new size.
    if (const auto size = inputAt(script_, frame_ - 1).resize) surface_.resize(*size);
    surface_.newFrame();
    std::vector<std::string> dropped = surface_.takeDroppedPaths();
    for (std::string& path : applyScript(script_, frame_ - 1, scriptKeys_)) dropped.push_back(std::move(path));
    ImGui_ImplOpenGL3_NewFrame();
    ImGui::NewFrame();
    const ImGuiIO& io = ImGui::GetIO();
    const Vec2i fb = surface_.framebufferSize();
    const float fbScale = io.DisplaySize.x > 0.f ? static_cast<float>(fb.x) / io.DisplaySize.x : 1.f;
    viewer_.setFrameTime(stats_.ms.empty() ? 0.0 : stats_.ms.back());
    if (const EnvironmentEdit edit = inputAt(script_, frame_ - 1).environment; !edit.empty()) viewer_.editEnvironment(edit);
    if (const std::optional<int> row = inputAt(script_, frame_ - 1).openOutlier) viewer_.openOutlierRow(*row - 1);
    viewer_.buildFrame(fb, fbScale, dropped);
    ImGui::Render();
    glViewport(0, 0, fb.x, fb.y);
    glClearColor(0.08f, 0.08f, 0.09f, 1.f);
    glClear(GL_COLOR_BUFFER_BIT);
    viewer_.drawImage(fb);
    glViewport(0, 0, fb.x, fb.y);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    return fb;
  }

  // What the frame's keys asked to keep of the drawn frame: a screenshot, the 3D view, a recording.
  void saveRequests(Vec2i fb) {
    if (viewer_.takeScreenshotRequest()) saveFramebuffer("pathlab-screenshot", "screenshot ", fb, {Vec2i(0), fb});
    if (const std::optional<PixelRect> rect = viewer_.takeView3DExportRequest())
      saveFramebuffer("pathlab-3d", "3D view ", fb, *rect);
    if (viewer_.takeRecordingToggleRequest()) recording_.toggle(viewer_);
    recording_.capture(viewer_, fb);
  }

  // `rect` of the framebuffer as out/STEM-STAMP.png; the message line says where (or why not).
  void saveFramebuffer(const std::string& stem, const std::string& what, Vec2i fb, const PixelRect& rect) {
    try {
      const std::string path = freshStem("out", stem, {".png"}) + ".png";
      writePngRgba(path, rect.size, readFramebufferRgba(fb, rect.origin, rect.size));
      viewer_.showMessage(what + path);
    } catch (const std::exception& e) {
      viewer_.showMessage(e.what(), true);
    }
  }
};

void FrameLoop::report() const {
  if (!counted()) return;
  const RenderSnapshot& s = viewer_.a().snapshot();
  const Vec2i fb = surface_.framebufferSize();
  const std::string series =
      o_.reference.empty() ? std::string() : fmt::format("; {} error series", viewer_.errors().series().size());
  // The region the last frame drew (what the screenshot shows), then the resolution rendered:
  // they differ under --render-scale or a reference's size, and on a busy machine the shown
  // snapshot may still be a placeholder generation's.
  const PixelRect drawn = viewer_.a().drawn();
  std::string compare;
  if (viewer_.b().running()) {
    const PixelRect b = viewer_.b().drawn();
    compare = fmt::format(", B image {}x{}+{}+{} at {} spp", b.size.x, b.size.y, b.origin.x, b.origin.y,
                          viewer_.b().snapshot().samplesPerPixel);
  }
  if (const std::optional<PixelRect> v = viewer_.drawnView3D())
    compare += fmt::format(", 3D view {}x{}+{}+{}", v->size.x, v->size.y, v->origin.x, v->origin.y);
  // The generation: how often the render restarted (a test's proof that something did not).
  // How next-event estimation chooses lights in the scene shown (a relight may have changed it).
  const char* nee = viewer_.shownScene().lights().neeByContext() ? "bvh" : "power";
  std::cerr << fmt::format(
      "{}: {}x{} {}, image {}x{}+{}+{} at {} spp{}, rendered {}x{} (generation {}), next-event lights {}; {}{}\n",
      o_.screenshot.empty() ? "pathlab view" : o_.screenshot, fb.x, fb.y, o_.headless ? "offscreen" : "window",
      drawn.size.x, drawn.size.y, drawn.origin.x, drawn.origin.y, s.samplesPerPixel, compare, s.settings.width,
      s.settings.height, s.generation, nee, stats_.summary(), series);
  // Offscreen nobody reads the panel: its error line goes to standard error too.
  if (const std::string error = viewer_.shownError(); !error.empty())
    std::cerr << "pathlab view: shown: " << error << "\n";
}

}  // namespace

int runViewer(const ViewerOptions& o) {
  checkOptions(o);
  ViewerOptions options = o;
  std::vector<NamedPreset> presets = loadPresetsOf(options);
  std::vector<InputEvent> script = parseInputScript(o.script);
  if (!o.recordDir.empty()) prepareRecordDirectory(o.recordDir, o.force);  // refused before the scene loads
  const std::shared_ptr<const Scene> scene = loadStartScene(o);
  // A bad reference is refused before the window opens.
  if (!options.reference.empty()) options.referenceImage = std::make_shared<const Image>(readImage(options.reference));

  ImGuiContextScope imgui;
  const std::unique_ptr<Surface> surface = openSurface(o);
  const float uiScale = uiScaleOf(o, *surface);
  setUpFontsAndStyle(uiScale);
  OpenGl3Backend backend;
  {
    Viewer viewer(options, scene, std::move(presets));
    viewer.setUiScale(uiScale);
    FrameLoop loop(o, std::move(script), *surface, viewer);
    loop.run();
    loop.report();
    loop.finish();
  }  // the viewer (and its render threads) goes before the GL context
  return 0;
}

}  // namespace pathlab::ui
