// The viewer's frame and plumbing: panels and their requests, settings to the renderer, snapshots
// to the textures, scenes, presets, saving.
#include "ui/viewer.h"

#include "core/camera/image_size.h"
#include "core/film/image_io.h"
#include "core/render/inspection_report.h"
#include "ui/output_names.h"
#include "ui/technique_grid.h"
#include "ui/thread_priority.h"

#include <fmt/core.h>
#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <thread>

#ifndef PATHLAB_ASSETS_DIR
#define PATHLAB_ASSETS_DIR "assets"
#endif

namespace pathlab::ui {

namespace {

// Full-resolution images are shown at most this often: uploading and drawing a float frame costs
// llvmpipe several milliseconds of CPU that the render threads would otherwise get. Previews and
// the first image of a generation are shown at once.
constexpr double kRefreshSeconds = 0.25;
constexpr double kPyramidRefreshSeconds = 0.5;
// Render threads yield to the UI thread and llvmpipe's rasteriser threads (thread_priority.h).
constexpr int kRenderThreadNice = 10;
// An ordinary message fades after this long; an error stays until dismissed.
constexpr double kMessageSeconds = 12.0;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

Viewer::Viewer(const ViewerOptions& options, std::shared_ptr<const Scene> scene, std::vector<NamedPreset> presets)
    : estimator_(EstimatorState::from(options.settings)), imageView_(std::make_unique<ImageView>()) {
  scene_.scene = std::move(scene);
  scene_.path = options.scene;
  scene_.loader = SceneLoader(options.load);
  environment_ = EnvironmentState::from(options.load.environment, options.load.lightSelection);
  // A preset's camera: orbit from there.
  scene_.orbit = OrbitCamera(estimator_.settings.camera.value_or(scene_.scene->cameraDesc()), scene_.scene->boundsMin(),
                             scene_.scene->boundsMax());
  presets_.presets = std::move(presets);
  presets_.path = options.presetsFile;
  if (!options.preset.empty())
    for (size_t i = 0; i < presets_.presets.size(); ++i)
      if (presets_.presets[i].name == options.preset) presets_.current = static_cast<int>(i);
  run_.targetSpp = targetApplied_ = options.spp;
  run_.resolutionScale = options.renderScale;
  display_.exposure = options.exposure;
  display_.errorView = options.errorView;
  ui_.showUi = !options.hideUi;
  grid_.zMap = options.zMap;
  if (!options.techniqueMap.empty()) maps_ = parseMapView(options.techniqueMap);
  if (options.pyramidLength > 0) {
    pyramid_.show = true;
    pyramid_.length = options.pyramidLength;
  }
  fitEstimatorToCamera();
  applied_ = renderSettings(estimator_);
  // The first frame sets the real image size; start small so nothing big is rendered in vain.
  applied_.width = applied_.height = 64;
  RenderSettings initial = applied_;
  if (noTechniqueEnabled(initial)) initial.techniques = TechniqueSet::all();
  if (!options.reference.empty()) {
    // From the command line a bad reference is an error of the command, not a message.
    reference_.errors->setReference(readImage(options.reference), viewOf(renderSettings(estimator_), scene_.scene.get()),
                                    options.reference);
    convergence_.show = true;
  }
  convergence_.show = convergence_.show || options.convergencePanel;
  threads_ = options.threads;
  // Side B starts with A on the first frame (syncCompare), both at the window's size.
  if (!options.compare.empty() && !applyCompareConfig(compare_, options.compare, renderSettings(estimator_)))
    throw std::invalid_argument(compare_.error);
  renderer_ = makeRenderer(initial, 0);
  refreshSceneFiles();
}

std::unique_ptr<ProgressiveRenderer> Viewer::makeRenderer(const RenderSettings& settings, int lane) {
  auto renderer = std::make_unique<ProgressiveRenderer>(scene_.scene, settings,
                                                        compare_.on ? threadsPerSide(threads_) : threads_);
  renderer->setTargetSpp(run_.targetSpp);
  renderer->setThumbnailSide(pyramidImages_.side);
  renderer->setPassObserver(passObserver(lane));
  return renderer;
}

PassObserver Viewer::passObserver(int lane) const {
  // Errors are measured on the render thread after each full pass (no copy of the image, no wait
  // for the UI's refresh); the tracker outlives the renderer through this shared pointer.
  return [errors = reference_.errors, lane](const PassInfo& info, const Image& mean) { errors->observe(info, mean, lane); };
}

void Viewer::syncCompare() {
  if (compare_.on == (compareSide_.renderer != nullptr)) return;
  // Both sides start together (an equal-time comparison), each on its share of the threads: the
  // old renderers go first (joining their workers), then the new ones start.
  renderer_.reset();
  compareSide_.renderer.reset();
  RenderSettings a = applied_;
  if (noTechniqueEnabled(a)) a.techniques = TechniqueSet::all();
  renderer_ = makeRenderer(a, 0);
  pausedApplied_ = timingApplied_ = false;
  targetApplied_ = run_.targetSpp;
  // The new renderers count versions from the start again.
  snapshot_ = RenderSnapshot{};
  pyramidImages_.version = 0;
  mapImages_.version = 0;
  if (compare_.on) {
    CompareSide& b = compareSide_;
    b.applied = compareRenderSettings(compare_.b, a);
    if (noTechniqueEnabled(b.applied)) b.applied.techniques = TechniqueSet::all();
    b.renderer = makeRenderer(b.applied, 1);
    b.pausedApplied = false;
    b.targetApplied = run_.targetSpp;
    b.snapshot = RenderSnapshot{};
    if (!b.view) b.view = std::make_unique<ImageView>();
    b.view->setReference(reference_.errors->reference().get());
  } else {
    compareSide_ = CompareSide{};
  }
  forceRefresh_ = true;
}

void Viewer::applyCompareSettings() {
  CompareSide& b = compareSide_;
  if (!b.renderer) return;
  b.idle = noTechniqueEnabled(compare_.b.settings);
  const RenderSettings wanted = compareRenderSettings(compare_.b, renderSettings(estimator_));
  if (b.idle || wanted == b.applied) return;
  b.applied = wanted;
  try {
    b.renderer->setSettings(wanted);
    forceRefresh_ = true;
  } catch (const std::exception& e) {
    compare_.error = e.what();  // B keeps its previous settings; the panel says why
  }
}

bool Viewer::updateCompareImage() {
  CompareSide& b = compareSide_;
  if (!b.renderer) return false;
  const bool newGeneration = b.renderer->generation() != b.snapshot.generation;
  const bool due = forceRefresh_ || newGeneration || b.snapshot.preview || secondsSince(b.lastPoll) >= kRefreshSeconds;
  if (!due) return false;
  b.lastPoll = std::chrono::steady_clock::now();
  if (!b.renderer->snapshot(b.snapshot)) return false;
  b.view->upload(b.snapshot.image, b.snapshot.settings.width, b.snapshot.settings.height);
  return true;
}

void Viewer::swapCompareSides() {
  CompareSide& b = compareSide_;
  if (!compare_.on || !b.renderer) return;
  // The estimators change sides and so do their renderers and images: nothing restarts unless
  // side A shows the pyramid, maps or check, which only A renders.
  swapSides(compare_, estimator_);
  std::swap(renderer_, b.renderer);
  std::swap(applied_, b.applied);
  std::swap(imageView_, b.view);
  std::swap(snapshot_, b.snapshot);
  std::swap(pausedApplied_, b.pausedApplied);
  std::swap(targetApplied_, b.targetApplied);
  std::swap(run_.idleForNoTechnique, b.idle);
  renderer_->setPassObserver(passObserver(0));
  b.renderer->setPassObserver(passObserver(1));
  b.renderer->setTiming(false);
  renderer_->setTiming(timingApplied_);
  renderer_->setThumbnailSide(pyramidImages_.side);
  pyramidImages_.version = 0;
  mapImages_.version = 0;
  forceRefresh_ = true;
  showMessage("sides swapped: A is now " + describe(renderSettings(estimator_)));
}

Viewer::~Viewer() = default;  // the renderer cancels its pass and joins its worker

void Viewer::showMessage(const std::string& text, bool error) {
  ui_.message = text;
  ui_.messageIsError = error;
  ui_.messageTime = std::chrono::steady_clock::now();
}

void Viewer::buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths) {
  ImGuiIO& io = ImGui::GetIO();
  for (const std::string& path : droppedPaths) openDropped(path);
  pollSceneLoad();

  handleShortcuts();
  // Panels beside the image, never over it: the controls on the left, the pyramid on the right,
  // the convergence plot and technique table along the bottom.
  const float scale = ui_.scale;
  const std::optional<float> aspect = imageAspect();
  const float bottom = ui_.showUi && convergence_.show ? convergencePanelHeight(io.DisplaySize.y, scale) : 0.f;
  const float upper = io.DisplaySize.y - bottom;
  // At most 45 % of the width: the image is what the audience looks at.
  const float panelWidth = ui_.showUi ? std::min(380.f * scale, io.DisplaySize.x * 0.45f) : 0.f;
  const float pyramidWidth =
      ui_.showUi && pyramid_.show
          ? pyramidPanelWidth(pyramid_, estimator_.settings.maxLength, io.DisplaySize.x - panelWidth, upper, scale, aspect)
          : 0.f;
  // The room the panels leave; the image is the largest rectangle of its aspect in it, centred
  // (never cropped: the camera's vertical and horizontal field of view both stay whole).
  PixelRect room;
  room.origin = {static_cast<int>(panelWidth * framebufferScale), 0};
  room.size = {std::max(framebufferSize.x - room.origin.x - static_cast<int>(pyramidWidth * framebufferScale), 0),
               std::max(framebufferSize.y - static_cast<int>(bottom * framebufferScale), 0)};
  // The path inspector's window along the room's bottom: its table and bars never cover the image.
  inspectorRect_ = {};
  if (ui_.showUi && inspector_.on) {
    const int h = std::min(static_cast<int>(0.42f * static_cast<float>(room.size.y)),
                           static_cast<int>(340.f * scale * framebufferScale));
    room.size.y -= h;
    inspectorRect_ = {static_cast<float>(room.origin.x) / framebufferScale,
                      static_cast<float>(room.origin.y + room.size.y) / framebufferScale,
                      static_cast<float>(room.size.x) / framebufferScale, static_cast<float>(h) / framebufferScale};
  }
  PixelRect fitted = fitAspect(room, aspect);
  if (compare_.on) view3d_.on = false;  // one image beside the main one
  view3dRect_ = {};
  if (compare_.on || view3d_.on) {
    // Two images of the same shape, A left (or above), B (or the 3D view) right (or below).
    const auto [a, b] = splitRoom(room, aspect, static_cast<int>(8.f * scale * framebufferScale));
    fitted = a;
    (compare_.on ? compareSide_.rect : view3dRect_) = b;
  }
  imageOrigin_ = fitted.origin;
  imageSize_ = fitted.size;
  handleCamera(framebufferScale);
  updateReferenceState();

  PanelRequests requests;
  if (ui_.showUi) {
    drawSidePanel(panelWidth, upper, requests);
    if (pyramid_.show)
      drawPyramidWindow(pyramid_, pyramidImages_, estimator_, {io.DisplaySize.x - pyramidWidth, 0.f, pyramidWidth, upper},
                        scale);
    if (convergence_.show)
      drawConvergenceWindow(convergence_, reference_, snapshot_, {0.f, upper, io.DisplaySize.x, bottom}, scale, requests);
    if (inspectorRect_.height > 0.f) drawInspectorWindow(inspector_, inspectorRect_, requests);
  }
  if (ui_.showHelp) drawHelpWindow(ui_.showHelp);
  const float fbScale = io.DisplayFramebufferScale.x > 0.f ? io.DisplayFramebufferScale.x : 1.f;
  drawImageOverlay(ImageOverlay{
      ImVec2(static_cast<float>(imageOrigin_.x) / fbScale, static_cast<float>(imageOrigin_.y) / fbScale),
      ImVec2(static_cast<float>(imageSize_.x) / fbScale, static_cast<float>(imageSize_.y) / fbScale), &snapshot_,
      renderSettings(estimator_), shownDisplay(), errorViewProblem(), run_.idleForNoTechnique, run_.userPaused, scale,
      grid_.zMap, maps_.show ? mapViewName(maps_) : std::string(), compare_.on ? "A" : ""});
  if (compare_.on && compareSide_.renderer) {
    const PixelRect& r = compareSide_.rect;
    drawImageOverlay(ImageOverlay{
        ImVec2(static_cast<float>(r.origin.x) / fbScale, static_cast<float>(r.origin.y) / fbScale),
        ImVec2(static_cast<float>(r.size.x) / fbScale, static_cast<float>(r.size.y) / fbScale), &compareSide_.snapshot,
        compareRenderSettings(compare_.b, renderSettings(estimator_)), shownDisplay(), errorViewProblem(),
        compareSide_.idle, run_.userPaused, scale, std::nullopt, std::string(), "B"});
  }
  drawMapOverImage(fbScale);
  drawInspectorOverlay(inspectorOverlay_, inspector_,
                       ImVec2(static_cast<float>(imageOrigin_.x) / fbScale, static_cast<float>(imageOrigin_.y) / fbScale),
                       ImVec2(static_cast<float>(imageSize_.x) / fbScale, static_cast<float>(imageSize_.y) / fbScale),
                       {inspector_.inspectedSettings.width, inspector_.inspectedSettings.height}, scale);
  drawView3D(fbScale);
  carryOut(requests);
  syncEnvironment();

  fitEstimatorToCamera();  // a key or a panel may just have asked for lt through an orthographic camera
  RenderSettings& edited = estimator_.settings;
  // The image follows its area of the window (a resize is a new generation, like any other change).
  // ... unless a reference sets it: an error needs the same pixels.
  if (const std::optional<ReferenceView> view = reference_.errors->referenceView(); view && reference_.matchSize) {
    edited.width = view->width;
    edited.height = view->height;
  } else if (aspect) {
    // The longest side follows the window; the other the camera's aspect, not the rounding of a
    // scaled-down rectangle (at --render-scale 0.25 that would drift by a few percent).
    const int longest = std::max(imageSize_.x, imageSize_.y);
    const Vec2i size = imageSizeForAspect(aspect, std::nullopt, std::nullopt,
                                          std::max(1, static_cast<int>(static_cast<float>(longest) * run_.resolutionScale)));
    edited.width = size.x;
    edited.height = size.y;
  } else {
    edited.width = std::max(1, static_cast<int>(static_cast<float>(imageSize_.x) * run_.resolutionScale));
    edited.height = std::max(1, static_cast<int>(static_cast<float>(imageSize_.y) * run_.resolutionScale));
  }
  edited.pyramidLength = pyramid_.show ? std::min(pyramid_.length, edited.maxLength) : 0;
  // The maps read the pyramid's films: showing them makes the pyramid at least their length and
  // keeps its sampleable films (one restart); which map is shown is the viewer's alone.
  edited.techniqueMaps = maps_.show && edited.integrator != IntegratorKind::Pt;
  if (edited.techniqueMaps)
    edited.pyramidLength = std::max(edited.pyramidLength, std::min({maps_.length, edited.maxLength, kMaxPyramidLength}));
  if (pyramid_.show) {
    // Thumbnails as large as they are shown (no blocky upscaling on a projector), from the next pass.
    const int side =
        std::clamp(static_cast<int>(std::max(pyramid_.thumbnail.x, pyramid_.thumbnail.y) * framebufferScale), 32, 256);
    if (side != pyramidImages_.side) renderer_->setThumbnailSide(pyramidImages_.side = side);
  }
  syncCompare();
  if (imageSize_.x > 0 && imageSize_.y > 0) {  // a minimised window keeps rendering the old size
    applySettings();
    applyCompareSettings();
  }
  syncRenderer();
  updateInspector();
  updateView3D();
}

void Viewer::fitEstimatorToCamera() {
  RenderSettings& e = estimator_.settings;
  if (!e.camera.value_or(scene_.scene->cameraDesc()).orthographic) return;
  // Nothing connects to an orthographic camera and it has no lens: the estimator falls back
  // rather than the scene being refused.
  if (e.integrator == IntegratorKind::Lt) {
    e.integrator = IntegratorKind::Bpt;
    showMessage("light tracing cannot render through this scene's orthographic camera: switched to bpt");
  }
  if (e.lens.apertureRadius > 0.f) {
    e.lens.apertureRadius = 0.f;
    showMessage("an orthographic camera has no lens: the aperture is 0");
  }
}

void Viewer::updateView3D() {
  if (!view3d_.on) {
    // Its copy of the meshes and its scene go with it, once no frame draws its texture.
    if (!view3dTextureInUse_) sceneRaster_.reset();
    view3d_.particles.replay.reset();
    view3d_.particles.scene.reset();
    return;
  }
  if (!sceneRaster_) sceneRaster_ = std::make_unique<SceneRaster>();
  ensureView3DCamera(view3d_, *scene_.scene, estimator_.settings.camera.value_or(scene_.scene->cameraDesc()));
  // The particles follow the newest full pass of the image shown.
  if (!snapshot_.preview && snapshot_.settings.width > 0)
    refreshLightParticles(view3d_.particles, scene_.scene, snapshot_.settings, snapshot_.samplesPerPixel);
}

void Viewer::drawView3D(float fbScale) {
  view3dTextureInUse_ = view3d_.on && sceneRaster_ && view3d_.orbit && view3dRect_.size.x > 0 && view3dRect_.size.y > 0;
  if (!view3dTextureInUse_) return;
  const ImVec2 origin(static_cast<float>(view3dRect_.origin.x) / fbScale, static_cast<float>(view3dRect_.origin.y) / fbScale);
  const ImVec2 size(static_cast<float>(view3dRect_.size.x) / fbScale, static_cast<float>(view3dRect_.size.y) / fbScale);
  const RenderSettings& shown = snapshot_.settings.width > 0 ? snapshot_.settings : applied_;
  const Camera view = view3DCamera(view3d_, view3dRect_.size);
  std::string caption = "3D view: drag orbits, Shift+drag pans, wheel zooms (O hides it)";
  if (view3d_.particles.on)
    caption += view3d_.particles.error.empty()
                   ? fmt::format("\n{} light subpaths of pass {} (L)", view3d_.particles.subpaths.size(),
                                 view3d_.particles.pass)
                   : "\n" + view3d_.particles.error;
  drawView3DWindow(sceneRaster_->texture().imguiId(), view3DOverlay(view3d_, inspector_, *scene_.scene, shown, view),
                   origin, size, view3dRect_.size, caption, ui_.scale);
}

void Viewer::exportInspection() {
  if (!inspector_.on || !inspector_.result) {
    showMessage("nothing to export: K, then click a pixel of the image");
    return;
  }
  try {
    const std::string path = freshStem("out", "pathlab-paths", {".json"}) + ".json";
    writeTextAtomically(path, inspectionJson(inspector_.inspectedSettings, *inspector_.result).dump(2) + "\n");
    showMessage("wrote " + path);
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

void Viewer::updateInspector() {
  // The inspected image is the one shown: its settings (size, camera, estimator) once one arrived.
  const RenderSettings& shown = snapshot_.settings.width > 0 ? snapshot_.settings : applied_;
  if (!refreshInspection(inspector_, *scene_.scene, shown)) return;
  inspectorOverlay_ = InspectorOverlay{};
  if (inspector_.result) {
    const RenderSettings& s = inspector_.inspectedSettings;
    inspectorOverlay_ = inspectorOverlay(inspector_, Camera(s.camera.value_or(scene_.scene->cameraDesc()), s.width, s.height, s.lens));
  }
}

void Viewer::drawSidePanel(float width, float height, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(0.f, 0.f));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::Begin("pathlab", nullptr, flags);
  const std::string title = "pathlab  " + std::filesystem::path(scene_.path).filename().string();
  ImGui::TextUnformatted(title.c_str());
  const float helpWidth = ImGui::CalcTextSize("Help (F1)").x + 2.f * ImGui::GetStyle().FramePadding.x;
  const float right = ImGui::GetWindowContentRegionMax().x - helpWidth;
  if (ImGui::GetItemRectSize().x + ImGui::GetStyle().ItemSpacing.x < right - ImGui::GetStyle().WindowPadding.x)
    ImGui::SameLine(right);
  if (ImGui::SmallButton("Help (F1)")) ui_.showHelp = !ui_.showHelp;
  // A notice is not part of the picture: not drawn in the frame a screenshot (F12) captures, nor
  // while recording (errors still are).
  const bool transientShown =
      !ui_.screenshotRequested && !ui_.recording && secondsSince(ui_.messageTime) < kMessageSeconds;
  if (!ui_.message.empty() && (ui_.messageIsError || transientShown)) {
    ImGui::PushStyleColor(ImGuiCol_Text, ui_.messageIsError ? ImVec4(1.f, 0.35f, 0.35f, 1.f) : ImVec4(0.6f, 0.9f, 0.6f, 1.f));
    ImGui::TextWrapped("%s", ui_.message.c_str());
    ImGui::PopStyleColor();
    if (ui_.messageIsError && ImGui::SmallButton("dismiss")) ui_.message.clear();
  }
  if (ImGui::CollapsingHeader("Status", ImGuiTreeNodeFlags_DefaultOpen))
    drawStatusSection(snapshot_, estimatorWarning(warning_, scene_.scene.get(), snapshot_.settings), run_, ui_.frameMs,
                      requests);
  if (ImGui::CollapsingHeader("Estimator", ImGuiTreeNodeFlags_DefaultOpen))
    drawEstimatorSection(estimator_, grid_, run_.settingsError, snapshot_.counters, snapshot_.check.get());
  if (ImGui::CollapsingHeader("Path inspector and 3D view", inspector_.on || view3d_.on ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawInspectorSection(inspector_, view3d_, requests);
  if (ImGui::CollapsingHeader("Compare A | B", compare_.on ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawCompareSection(compare_, compareSide_.snapshot, requests);
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen))
    drawDisplaySection(display_, run_, pyramid_, snapshot_.image);
  if (ImGui::CollapsingHeader("Technique maps", maps_.show ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawTechniqueMapSection(maps_, estimator_.settings.maxLength, mapImages_.texture.empty());
  if (ImGui::CollapsingHeader("Reference and error", convergence_.show ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawReferenceSection(reference_, convergence_, display_, estimator_.settings, snapshot_.image, requests);
  if (ImGui::CollapsingHeader("Environment", environment_.applied.spec.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    drawEnvironmentSection(environment_);
  if (ImGui::CollapsingHeader("Scene and camera"))
    drawSceneSection(scene_, estimator_.settings.camera.has_value(), requests);
  if (ImGui::CollapsingHeader("Presets", presets_.presets.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    drawPresetSection(presets_, requests);
  ImGui::End();
}

void Viewer::carryOut(const PanelRequests& requests) {
  for (const Action action : requests.actions) perform(action);
  if (requests.openScene) openScene(*requests.openScene);
  if (requests.loadReference) loadReference(*requests.loadReference);
  if (requests.preset) applyPreset(*requests.preset);
  if (requests.rescanScenes) refreshSceneFiles();
  if (requests.returnToReferenceView) returnToReferenceView();
  if (requests.exportErrorCsv) exportErrorCsv();
  if (requests.compareConfig && applyCompareConfig(compare_, *requests.compareConfig, renderSettings(estimator_)))
    showMessage("B: " + describe(compareRenderSettings(compare_.b, renderSettings(estimator_))));
}

bool Viewer::pollImage() {
  if (secondsSince(lastPriorityCheck_) > 1.0) {
    // New TBB workers appear lazily; they inherit nothing from the UI's wishes.
    lowerRenderThreadPriority(kRenderThreadNice);
    lastPriorityCheck_ = std::chrono::steady_clock::now();
  }
  const bool pyramid = pyramid_.show && updatePyramid();
  const bool maps = maps_.show && updateMaps();
  const bool compare = updateCompareImage();
  const bool image = updateImage();
  bool reference = false;
  if (reference_.errors->referenceVersion() != reference_.uploadedVersion) {
    reference_.uploadedVersion = reference_.errors->referenceVersion();
    const std::shared_ptr<const Image> r = reference_.errors->reference();
    imageView_->setReference(r.get());
    if (compareSide_.view) compareSide_.view->setReference(r.get());
    reference = true;
  }
  // New points arrive on the render thread; the plot redraws when they do.
  const bool points = convergence_.show && reference_.errors->version() != convergence_.seriesVersion;
  return image || compare || pyramid || maps || reference || points;
}

void Viewer::applySettings() {
  // The renderer cannot run an empty technique set: idle and show black until one is enabled.
  run_.idleForNoTechnique = noTechniqueEnabled(estimator_.settings);
  const RenderSettings wanted = renderSettings(estimator_);
  if (run_.idleForNoTechnique || wanted == applied_) return;
  applied_ = wanted;
  try {
    renderer_->setSettings(wanted);
    run_.settingsError.clear();
    forceRefresh_ = true;
  } catch (const std::exception& e) {
    // The renderer keeps its previous settings; the panel shows why until the next change.
    run_.settingsError = e.what();
  }
}

void Viewer::syncRenderer() {
  if (run_.paused() != pausedApplied_) renderer_->setPaused(pausedApplied_ = run_.paused());
  if (run_.targetSpp != targetApplied_) renderer_->setTargetSpp(targetApplied_ = run_.targetSpp);
  if (CompareSide& b = compareSide_; b.renderer) {
    // B pauses with the user, or when it enables no technique; not when only A has none.
    const bool paused = run_.userPaused || b.idle;
    if (paused != b.pausedApplied) b.renderer->setPaused(b.pausedApplied = paused);
    if (run_.targetSpp != b.targetApplied) b.renderer->setTargetSpp(b.targetApplied = run_.targetSpp);
  }
  // Per-technique timing costs two clock reads a connection: only while its table is shown.
  const bool timing = ui_.showUi && convergence_.show;
  if (timing != timingApplied_) renderer_->setTiming(timingApplied_ = timing);
}

bool Viewer::updateImage() {
  const bool newGeneration = renderer_->generation() != snapshot_.generation;
  const bool due = forceRefresh_ || newGeneration || snapshot_.preview || secondsSince(lastPoll_) >= kRefreshSeconds;
  if (!due) return false;
  forceRefresh_ = false;
  lastPoll_ = std::chrono::steady_clock::now();
  if (!renderer_->snapshot(snapshot_)) return false;
  imageView_->upload(snapshot_.image, snapshot_.settings.width, snapshot_.settings.height);
  return true;
}

bool Viewer::updatePyramid() {
  PyramidImages& p = pyramidImages_;
  const bool due = forceRefresh_ || secondsSince(p.lastPoll) >= kPyramidRefreshSeconds;
  if (due) p.lastPoll = std::chrono::steady_clock::now();
  const bool fresh = due && renderer_->pyramid(p.thumbnails, p.version);
  // Re-tone the thumbnails we have when their display changes (exposure mode, tone map, ...).
  const bool retone = !(p.toned == display_) || p.tonedOwnExposure != pyramid_.ownExposure;
  if (!fresh && !retone) return false;
  p.toned = display_;
  p.tonedOwnExposure = pyramid_.ownExposure;
  p.textures.resize(2 * p.thumbnails.size());
  for (size_t i = 0; i < p.thumbnails.size(); ++i) {
    const Image* images[2] = {&p.thumbnails[i].weighted, &p.thumbnails[i].unweighted};
    for (int u = 0; u < 2; ++u) {
      if (images[u]->width <= 0) continue;
      // Own exposure: every technique visible although their magnitudes differ by orders of
      // magnitude. Common exposure (the image's): the weighted shares compare directly.
      DisplaySettings d = display_;
      if (pyramid_.ownExposure) d.exposure = autoExposure(*images[u]);
      const std::vector<uint8_t> rgba = toRgba8(*images[u], d);
      p.textures[2 * i + static_cast<size_t>(u)].uploadRgba8(images[u]->width, images[u]->height, rgba.data());
    }
  }
  return true;
}

bool Viewer::updateMaps() {
  MapImages& m = mapImages_;
  const bool due = forceRefresh_ || secondsSince(m.lastPoll) >= kPyramidRefreshSeconds;
  if (due) m.lastPoll = std::chrono::steady_clock::now();
  const bool fresh = due && renderer_->techniqueMaps(m.lum, m.version);
  if (!fresh && m.coloured == maps_) return false;
  m.coloured = maps_;
  const Image map = mapImage(m.lum, maps_);
  if (map.width <= 0) {
    m.texture = Texture();
    return fresh;
  }
  std::vector<uint8_t> rgba(4 * static_cast<size_t>(map.width) * static_cast<size_t>(map.height), 255);
  for (size_t i = 0; i < rgba.size() / 4; ++i)
    for (size_t c = 0; c < 3; ++c)
      rgba[4 * i + c] = static_cast<uint8_t>(std::clamp(map.rgb[3 * i + c], 0.f, 1.f) * 255.f + 0.5f);
  m.texture.uploadRgba8(map.width, map.height, rgba.data());
  return true;
}

void Viewer::drawMapOverImage(float fbScale) {
  const Texture& t = mapImages_.texture;
  if (!maps_.show || t.empty() || imageSize_.x <= 0 || imageSize_.y <= 0) return;
  // Fitted into the image's rectangle like the image (ImageView::draw), centred: the map has the
  // image's aspect, so it covers the image exactly.
  const PixelRect r =
      fitAspect({imageOrigin_, imageSize_}, static_cast<float>(t.width()) / static_cast<float>(t.height()));
  const ImVec2 p0(static_cast<float>(r.origin.x) / fbScale, static_cast<float>(r.origin.y) / fbScale);
  const ImVec2 p1(static_cast<float>(r.origin.x + r.size.x) / fbScale, static_cast<float>(r.origin.y + r.size.y) / fbScale);
  ImGui::GetBackgroundDrawList()->AddImage(t.imguiId(), p0, p1);
}

void Viewer::waitForPyramid(double seconds) {
  if (!pyramid_.show || renderSettings(estimator_).pyramidLength == 0) return;
  const auto start = std::chrono::steady_clock::now();
  std::vector<TechniqueThumbnail> probe;
  uint64_t version = pyramidImages_.version;
  // The renderer publishes the thumbnails of a pass just after its image.
  while (secondsSince(start) < seconds) {
    if (renderer_->pyramid(probe, version) && !probe.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  forceRefresh_ = true;
}

void Viewer::drawImage(Vec2i framebufferSize) {
  drawn_ = {};
  compareSide_.drawn = {};
  if (compareSide_.renderer && !compareSide_.idle)
    compareSide_.drawn = compareSide_.view->draw(compareSide_.rect.origin, compareSide_.rect.size, framebufferSize.y,
                                                 shownDisplay());
  if (sceneRaster_ && view3d_.on && view3d_.orbit)
    sceneRaster_->draw(scene_.scene, view3DCameraDesc(view3d_), view3dRect_.size, view3d_.cullBackFaces);
  if (run_.idleForNoTechnique) return;  // black: nothing is estimated
  drawn_ = imageView_->draw(imageOrigin_, imageSize_, framebufferSize.y, shownDisplay());
}

std::optional<float> Viewer::imageAspect() const {
  // A reference sets the pixels (the error needs the same ones), and with them the shape.
  if (const std::optional<ReferenceView> view = reference_.errors->referenceView(); view && reference_.matchSize)
    return static_cast<float>(view->width) / static_cast<float>(std::max(view->height, 1));
  // The orbit/fly override carries the scene camera's aspect (OrbitCamera keeps it); a preset's
  // camera has none of its own and shows the same scene: it keeps the scene camera's too.
  return cameraAspect(estimator_.settings.camera, scene_.scene->cameraDesc());
}

void Viewer::openScene(const std::string& path) {
  // Lit as the shown scene is (the command line's environment, or the one loaded since).
  scene_.loader.start(path, environment_.applied, environment_.read);
  showMessage("loading " + path + " ...");
}

void Viewer::pollSceneLoad() {
  std::optional<SceneLoadResult> r = scene_.loader.poll();
  if (!r) return;
  const bool relit = r->path == scene_.path && r->environment && !(*r->environment == environment_.applied);
  if (!takeLoadedEnvironment(*r)) {
    showMessage(r->error + (relit ? " (the previous environment is kept)" : " (the previous scene is kept)"), true);
    return;
  }
  // A reload keeps the view (the file is being edited); another scene starts at its own camera.
  const bool reload = r->path == scene_.path;
  // The error against a reference of another scene (or of the file before it was edited) is
  // meaningless: drop it (the plot keeps what was measured against it).
  const bool hadReference = reference_.errors->reference() != nullptr;
  reference_.errors->dropReference();
  scene_.scene = r->scene;
  scene_.path = r->path;
  if (!reload) resetCamera();
  fitEstimatorToCamera();
  applied_ = renderSettings(estimator_);
  if (noTechniqueEnabled(applied_)) applied_.techniques = TechniqueSet::all();
  try {
    renderer_->setScene(scene_.scene, applied_);
    run_.settingsError.clear();
  } catch (const std::exception& e) {
    run_.settingsError = e.what();
  }
  if (CompareSide& b = compareSide_; b.renderer) {
    b.applied = compareRenderSettings(compare_.b, applied_);
    if (noTechniqueEnabled(b.applied)) b.applied.techniques = TechniqueSet::all();
    try {
      b.renderer->setScene(scene_.scene, b.applied);
    } catch (const std::exception& e) {
      compare_.error = e.what();
    }
  }
  forceRefresh_ = true;
  refreshSceneFiles();
  const Scene& scene = *scene_.scene;
  std::string text =
      relit ? "environment: " + describe(environment_.applied)
            : fmt::format("loaded {}: {} triangles, {} lights, {:.1f} MB of geometry", scene_.path, scene.triangleCount(),
                  scene.lights().size(), double(scene.geometryBytes()) / 1e6);
  for (const std::string& w : scene.warnings()) text += "; warning: " + w;
  if (hadReference)
    text += relit ? "; the reference was dropped (it was lit otherwise)"
                  : "; the reference was dropped (it showed the previous scene)";
  // A relight right after a failed one (its strength, say) must not hide the error unread.
  if (relit && ui_.messageIsError && !ui_.message.empty()) return;
  showMessage(text);
}

void Viewer::refreshSceneFiles() {
  std::vector<std::string>& files = scene_.files;
  files.clear();
  std::vector<std::filesystem::path> dirs = {std::filesystem::path(scene_.path).parent_path(), PATHLAB_ASSETS_DIR};
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (dir.empty() || !std::filesystem::is_directory(dir, ec)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".gltf" && ext != ".glb") continue;
      std::string p = std::filesystem::relative(entry.path(), ec).string();
      if (ec || p.empty() || p.starts_with("../../")) p = entry.path().string();
      if (std::find(files.begin(), files.end(), p) == files.end()) files.push_back(p);
    }
  }
  std::sort(files.begin(), files.end());
}

void Viewer::resetCamera() {
  scene_.orbit = OrbitCamera(scene_.scene->cameraDesc(), scene_.scene->boundsMin(), scene_.scene->boundsMax());
  estimator_.settings.camera.reset();
}

void Viewer::applyPreset(int index) {
  const int n = static_cast<int>(presets_.presets.size());
  if (n == 0) return;
  presets_.current = (index % n + n) % n;
  const NamedPreset& p = presets_.presets[static_cast<size_t>(presets_.current)];
  ui::applyPreset(estimator_, p);
  if (p.camera) scene_.orbit = OrbitCamera(*p.camera, scene_.scene->boundsMin(), scene_.scene->boundsMax());
  // A preset with a side B sets both sides (checked when the presets were loaded); one without
  // leaves the comparison as it is.
  if (p.compare && !applyCompareConfig(compare_, *p.compare, renderSettings(estimator_))) {
    showMessage("preset " + p.name + ": " + compare_.error, true);
    return;
  }
  showMessage("preset: " + p.name);
}

void Viewer::saveImage() {
  if (snapshot_.image.width <= 0 || snapshot_.preview) {
    showMessage("nothing to save yet: wait for the first full-resolution pass", true);
    return;
  }
  try {
    const RenderSnapshot& b = compareSide_.snapshot;
    const bool both = compareSide_.renderer && b.image.width > 0 && !b.preview;
    const std::string stem = freshStem("out", "pathlab", {".exr", ".png", "-B.exr", "-B.png"});
    writeImage(stem + ".exr", snapshot_.image);
    writeImage(stem + ".png", snapshot_.image, display_.exposure);
    if (both) {
      // Side B beside it, so each side can be compared with a render of its configuration.
      writeImage(stem + "-B.exr", b.image);
      writeImage(stem + "-B.png", b.image, display_.exposure);
      showMessage(fmt::format("saved {}.exr/.png (A, {} spp) and {}-B.exr/.png (B, {} spp)", stem,
                              snapshot_.samplesPerPixel, stem, b.samplesPerPixel));
    } else {
      showMessage(fmt::format("saved {}.exr and .png ({} spp)", stem, snapshot_.samplesPerPixel));
    }
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

}  // namespace pathlab::ui
