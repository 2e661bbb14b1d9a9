// The viewer's frame: its layout, panels and overlays, the requests the panels make, and the two
// sides' settings, pause and snapshots.
#include "ui/viewer.h"

#include "core/camera/image_size.h"
#include "core/film/image_io.h"
#include "core/maps/map_colours.h"
#include "ui/lane/thread_priority.h"

#include <imgui.h>

#include <algorithm>
#include <filesystem>
#include <thread>

namespace pathlab::ui {

namespace {

// Render threads yield to the UI thread and llvmpipe's rasteriser threads (thread_priority.h).
constexpr int kRenderThreadNice = 10;
// An ordinary message fades after this long; an error stays until dismissed.
constexpr double kMessageSeconds = 12.0;

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

ImVec2 toImGui(Vec2i framebufferPixels, float fbScale) {
  return ImVec2(static_cast<float>(framebufferPixels.x) / fbScale, static_cast<float>(framebufferPixels.y) / fbScale);
}

}  // namespace

Viewer::Viewer(const ViewerOptions& options, std::shared_ptr<const Scene> scene, std::vector<NamedPreset> presets)
    : estimator_(EstimatorState::from(options.settings)),
      scenes_(options, std::move(scene), ui_.message),
      presets_(std::move(presets), options),
      sides_(options.threads, reference_.errors) {
  run_.targetSpp = options.spp;
  run_.resolutionScale = options.renderScale;
  display_.exposure = options.exposure;
  display_.errorView = options.errorView;
  ui_.showUi = !options.hideUi;
  grid_.zMap = options.zMap;
  if (!options.techniqueMap.empty()) maps_ = parseMapView(options.techniqueMap);
  if (options.outliers > 0) {
    outliers_.on = true;
    outliers_.count = options.outliers;
  }
  if (options.pyramidLength > 0) {
    pyramid_.show = true;
    pyramid_.length = options.pyramidLength;
  }
  fitEstimatorToCamera();
  // The first frame sets the real image size; start small so nothing big is rendered in vain.
  RenderSettings initial = renderSettings(estimator_);
  initial.width = initial.height = 64;
  if (!options.reference.empty()) {
    // From the command line a bad reference is an error of the command, not a message.
    reference_.errors->setReference(options.referenceImage ? *options.referenceImage : readImage(options.reference),
                                    viewOf(renderSettings(estimator_), &this->scene()), options.reference);
    convergence_.show = true;
  }
  convergence_.show = convergence_.show || options.convergencePanel;
  // Side B starts with A on the first frame (syncCompare), both at the window's size.
  if (!options.compare.empty() && !applyCompareConfig(compare_, options.compare, renderSettings(estimator_)))
    throw std::invalid_argument(compare_.error);
  sides_.startA(scenes_.scene(), initial, compare_.on, laneStart());
}

Sides::Start Viewer::laneStart() const { return {run_.targetSpp, techniqueImages_.pyramid.side}; }

RenderSettings Viewer::wantedSettings(const RenderLane& lane) const {
  const RenderSettings a = renderSettings(estimator_);
  return &lane == &this->a() ? a : compareRenderSettings(compare_.b, a);
}

void Viewer::syncCompare() {
  if (!sides_.setComparing(compare_.on, scenes_.scene(), compare_.b, laneStart())) return;
  // The new renderers count versions from the start again.
  techniqueImages_.restart();
  forceRefresh_ = true;
}

void Viewer::swapCompareSides() {
  if (!compare_.on || !b().running()) return;
  // The estimators change sides and so do their renderers and images: nothing restarts unless
  // side A shows the pyramid, maps or check, which only A renders.
  swapSides(compare_, estimator_);
  sides_.swap();
  a().renderer().setThumbnailSide(techniqueImages_.pyramid.side);
  techniqueImages_.restart();
  forceRefresh_ = true;
  showMessage("sides swapped: A is now " + describe(renderSettings(estimator_)));
}

Viewer::~Viewer() = default;  // the renderer cancels its pass and joins its worker

void Viewer::showMessage(const std::string& text, bool error) {
  ui_.message.show(text, error);
}

void Viewer::buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths) {
  for (const std::string& path : droppedPaths) scenes_.openDropped(path);
  pollSceneLoad();
  handleShortcuts();
  const FrameLayout layout = layOut(framebufferSize, framebufferScale);
  handleCamera(framebufferScale);
  updateReferenceState();
  PanelRequests requests;
  if (ui_.showUi) drawPanels(layout, requests);
  if (ui_.showHelp) drawHelpWindow(ui_.showHelp);
  drawOverImages();
  carryOut(requests);
  scenes_.syncEnvironment();
  fitEstimatorToCamera();  // a key or a panel may just have asked for lt through an orthographic camera
  fitEstimatorToFrame(layout.aspect, framebufferScale);
  syncCompare();
  if (imageSize().x > 0 && imageSize().y > 0) applySettings();  // a minimised window keeps rendering the old size
  syncRenderers();
  inspect_.update(scenes_.scene(), shownSettings(), a().snapshot(),
                  estimator_.settings.camera.value_or(scene().cameraDesc()));
}

Viewer::FrameLayout Viewer::layOut(Vec2i framebufferSize, float framebufferScale) {
  const ImGuiIO& io = ImGui::GetIO();
  // Panels beside the image, never over it: the controls on the left, the pyramid on the right,
  // the convergence plot and technique table along the bottom.
  FrameLayout l;
  const float scale = ui_.scale;
  l.aspect = imageAspect();
  l.bottom = ui_.showUi && convergence_.show ? convergencePanelHeight(io.DisplaySize.y, scale) : 0.f;
  l.upper = io.DisplaySize.y - l.bottom;
  // At most 45 % of the width: the image is what the audience looks at.
  l.panelWidth = ui_.showUi ? std::min(380.f * scale, io.DisplaySize.x * 0.45f) : 0.f;
  l.pyramidWidth = ui_.showUi && pyramid_.show ? pyramidPanelWidth(pyramid_, estimator_.settings.maxLength,
                                                                   io.DisplaySize.x - l.panelWidth, l.upper, scale, l.aspect,
                                                                   techniqueImages_.pyramid.hasMerges(),
                                                                   techniqueImages_.pyramid.hasEquiangular())
                                               : 0.f;
  // The room the panels leave; the image is the largest rectangle of its aspect in it, centred
  // (never cropped: the camera's vertical and horizontal field of view both stay whole).
  PixelRect room;
  room.origin = {static_cast<int>(l.panelWidth * framebufferScale), 0};
  room.size = {std::max(framebufferSize.x - room.origin.x - static_cast<int>(l.pyramidWidth * framebufferScale), 0),
               std::max(framebufferSize.y - static_cast<int>(l.bottom * framebufferScale), 0)};
  room = inspect_.placeWindow(room, ui_.showUi, scale, framebufferScale);
  PixelRect fitted = fitAspect(room, l.aspect);
  if (compare_.on) inspect_.view3d.on = false;  // one image beside the main one
  inspect_.view3dRect = {};
  if (compare_.on || inspect_.view3d.on) {
    // Two images of the same shape, A left (or above), B (or the 3D view) right (or below).
    const auto [a, b] = splitRoom(room, l.aspect, static_cast<int>(8.f * scale * framebufferScale));
    fitted = a;
    (compare_.on ? this->b().rect : inspect_.view3dRect) = b;
  }
  a().rect = fitted;
  return l;
}

void Viewer::drawPanels(const FrameLayout& l, PanelRequests& requests) {
  const ImGuiIO& io = ImGui::GetIO();
  drawSidePanel(l.panelWidth, l.upper, requests);
  if (pyramid_.show)
    drawPyramidWindow(pyramid_, techniqueImages_.pyramid, estimator_,
                      {io.DisplaySize.x - l.pyramidWidth, 0.f, l.pyramidWidth, l.upper}, ui_.scale);
  if (convergence_.show)
    drawConvergenceWindow(convergence_, reference_, a().snapshot(), {0.f, l.upper, io.DisplaySize.x, l.bottom},
                          ui_.scale, requests);
  inspect_.drawWindow(requests);
}

void Viewer::drawOverImages() {
  const ImGuiIO& io = ImGui::GetIO();
  const float fbScale = io.DisplayFramebufferScale.x > 0.f ? io.DisplayFramebufferScale.x : 1.f;
  // The captions of each side; the pyramid's and the maps' belong to A only.
  for (const RenderLane* lane : {&a(), &b()}) {
    if (!lane->running() || (lane == &b() && !compare_.on)) continue;
    const bool isA = lane == &a();
    drawImageOverlay(ImageOverlay{toImGui(lane->rect.origin, fbScale), toImGui(lane->rect.size, fbScale),
                                  &lane->snapshot(), wantedSettings(*lane), shownDisplay(), errorViewProblem(),
                                  lane->idle(), run_.userPaused, ui_.scale, isA ? grid_.zMap : std::nullopt,
                                  isA && maps_.show ? mapViewName(maps_) : std::string(),
                                  compare_.on ? (isA ? "A" : "B") : ""});
  }
  techniqueImages_.drawMap(maps_, a().rect, fbScale);
  drawChainDensity(fbScale);
  inspect_.drawOverlays(scene(), shownSettings(), toImGui(a().rect.origin, fbScale), toImGui(a().rect.size, fbScale),
                        fbScale, ui_.scale);
  drawOutlierMarkers(outliers_, toImGui(a().rect.origin, fbScale), toImGui(a().rect.size, fbScale),
                     shownSettings(), ui_.scale);
}

void Viewer::fitEstimatorToFrame(std::optional<float> aspect, float framebufferScale) {
  RenderSettings& edited = estimator_.settings;
  // The image follows its area of the window (a resize is a new generation, like any other change).
  // ... unless a reference sets it: an error needs the same pixels.
  if (const std::optional<ReferenceView> view = reference_.errors->referenceView(); view && reference_.matchSize) {
    edited.width = view->width;
    edited.height = view->height;
  } else if (aspect) {
    // The longest side follows the window; the other the camera's aspect, not the rounding of a
    // scaled-down rectangle (at --render-scale 0.25 that would drift by a few percent).
    const int longest = std::max(imageSize().x, imageSize().y);
    const Vec2i size = imageSizeForAspect(aspect, std::nullopt, std::nullopt,
                                          std::max(1, static_cast<int>(static_cast<float>(longest) * run_.resolutionScale)));
    edited.width = size.x;
    edited.height = size.y;
  } else {
    edited.width = std::max(1, static_cast<int>(static_cast<float>(imageSize().x) * run_.resolutionScale));
    edited.height = std::max(1, static_cast<int>(static_cast<float>(imageSize().y) * run_.resolutionScale));
  }
  const bool metropolis = edited.integrator == IntegratorKind::Mlt;  // no per-technique images
  edited.pyramidLength = pyramid_.show && !metropolis ? std::min(pyramid_.length, edited.maxLength) : 0;
  // The maps read the pyramid's films: showing them makes the pyramid at least their length and
  // keeps its sampleable films (one restart); which map is shown is the viewer's alone.
  edited.techniqueMaps = maps_.show && edited.integrator != IntegratorKind::Pt && !metropolis;
  // The variance maps with them, so that choosing one restarts nothing.
  edited.varianceMaps = edited.techniqueMaps;
  if (edited.techniqueMaps)
    edited.pyramidLength = std::max(edited.pyramidLength, std::min({maps_.length, edited.maxLength, kMaxPyramidLength}));
  if (pyramid_.show) {
    // Thumbnails as large as they are shown (no blocky upscaling on a projector), from the next pass.
    const int side =
        std::clamp(static_cast<int>(std::max(pyramid_.thumbnail.x, pyramid_.thumbnail.y) * framebufferScale), 32, 256);
    if (side != techniqueImages_.pyramid.side) a().renderer().setThumbnailSide(techniqueImages_.pyramid.side = side);
  }
}

void Viewer::fitEstimatorToCamera() {
  RenderSettings& e = estimator_.settings;
  if (!e.camera.value_or(scene().cameraDesc()).orthographic) return;
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

void Viewer::drawSidePanel(float width, float height, PanelRequests& requests) {
  ImGui::SetNextWindowPos(ImVec2(0.f, 0.f));
  ImGui::SetNextWindowSize(ImVec2(width, height));
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                 ImGuiWindowFlags_NoTitleBar | ImGuiWindowFlags_NoSavedSettings |
                                 ImGuiWindowFlags_NoBringToFrontOnFocus;
  ImGui::Begin("pathlab", nullptr, flags);
  const std::string title = "pathlab  " + std::filesystem::path(scenes_.path()).filename().string();
  ImGui::TextUnformatted(title.c_str());
  const float helpWidth = ImGui::CalcTextSize("Help (F1)").x + 2.f * ImGui::GetStyle().FramePadding.x;
  const float right = ImGui::GetWindowContentRegionMax().x - helpWidth;
  if (ImGui::GetItemRectSize().x + ImGui::GetStyle().ItemSpacing.x < right - ImGui::GetStyle().WindowPadding.x)
    ImGui::SameLine(right);
  if (ImGui::SmallButton("Help (F1)")) ui_.showHelp = !ui_.showHelp;
  // A notice is not part of the picture: not drawn in the frame a screenshot (F12) captures, nor
  // while recording (errors still are).
  const bool transientShown =
      !ui_.screenshotRequested && !ui_.recording && secondsSince(ui_.message.time) < kMessageSeconds;
  const MessageLine& m = ui_.message;
  if (!m.text.empty() && (m.isError || transientShown)) {
    ImGui::PushStyleColor(ImGuiCol_Text, m.isError ? ImVec4(1.f, 0.35f, 0.35f, 1.f) : ImVec4(0.6f, 0.9f, 0.6f, 1.f));
    ImGui::TextWrapped("%s", m.text.c_str());
    ImGui::PopStyleColor();
    if (m.isError && ImGui::SmallButton("dismiss")) ui_.message.text.clear();
  }
  if (ImGui::CollapsingHeader("Status", ImGuiTreeNodeFlags_DefaultOpen))
    drawStatusSection(a().snapshot(), estimatorWarning(warning_, &scene(), a().snapshot().settings), run_,
                      ui_.frameMs, requests);
  if (ImGui::CollapsingHeader("Estimator", ImGuiTreeNodeFlags_DefaultOpen))
    drawEstimatorSection(estimator_, grid_, a().refused(), a().snapshot().counters, a().snapshot().check.get(),
                         a().snapshot().mlt.get(),
                         MergeRadiusNow{&a().snapshot().settings, a().snapshot().samplesPerPixel, scene().bounds().radius},
                         sampledFamilies(renderSettings(estimator_), scene()), a().snapshot().lightPaths.get());
  if (ImGui::CollapsingHeader("Path inspector and 3D view",
                              inspect_.inspector.on || inspect_.view3d.on ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawInspectorSection(inspect_.inspector, inspect_.view3d, requests);
  if (ImGui::CollapsingHeader("Outliers (fireflies)", outliers_.on ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawOutlierSection(outliers_, estimator_.settings, a().snapshot(), requests);
  if (ImGui::CollapsingHeader("Compare A | B", compare_.on ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawCompareSection(compare_, b().snapshot(), b().refused(), requests);
  if (ImGui::CollapsingHeader("Display", ImGuiTreeNodeFlags_DefaultOpen))
    drawDisplaySection(display_, run_, pyramid_, a().snapshot().image);
  if (ImGui::CollapsingHeader("Technique maps", maps_.show ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawTechniqueMapSection(maps_, estimator_.settings.maxLength, pyramidFamilies(estimator_.settings, scene()),
                            techniqueImages_.maps.texture.empty());
  if (ImGui::CollapsingHeader("Reference and error", convergence_.show ? ImGuiTreeNodeFlags_DefaultOpen : 0))
    drawReferenceSection(reference_, convergence_, display_, estimator_.settings, a().snapshot().image, requests);
  if (ImGui::CollapsingHeader("Environment",
                              scenes_.environment().applied.spec.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    drawEnvironmentSection(scenes_.environment());
  if (ImGui::CollapsingHeader("Scene and camera"))
    drawSceneSection(scenes_.state(), estimator_.settings.camera.has_value(), requests);
  if (ImGui::CollapsingHeader("Presets", presets_.state().presets.empty() ? 0 : ImGuiTreeNodeFlags_DefaultOpen))
    drawPresetSection(presets_.state(), requests);
  ImGui::End();
}

void Viewer::carryOut(const PanelRequests& requests) {
  for (const Action action : requests.actions) perform(action);
  if (requests.openScene) scenes_.open(*requests.openScene);
  if (requests.loadReference) loadReference(*requests.loadReference);
  if (requests.preset) presets_.apply(*requests.preset, presetTarget());
  if (requests.rescanScenes) scenes_.refreshFiles();
  if (requests.returnToReferenceView) returnToReferenceView();
  if (requests.exportErrorCsv) exportErrorCsv();
  if (requests.openOutlier) openOutlierRow(*requests.openOutlier);
  if (requests.compareConfig && applyCompareConfig(compare_, *requests.compareConfig, renderSettings(estimator_)))
    showMessage("B: " + describe(compareRenderSettings(compare_.b, renderSettings(estimator_))));
}

bool Viewer::pollImage() {
  if (secondsSince(lastPriorityCheck_) > 1.0) {
    // New TBB workers appear lazily; they inherit nothing from the UI's wishes.
    lowerRenderThreadPriority(kRenderThreadNice);
    lastPriorityCheck_ = std::chrono::steady_clock::now();
  }
  const bool techniques = techniqueImages_.update(a().renderer(), pyramid_, maps_, display_, forceRefresh_);
  const bool image = sides_.poll(forceRefresh_);
  const PathInspectorState& inspector = inspect_.inspector;
  outliers_.hold = inspector.on && inspector.pinned && *inspector.pinned == outliers_.list.settings;
  const bool outliers = outliers_.on && a().running() && updateOutlierList(outliers_, a().renderer(), scene());
  forceRefresh_ = false;
  bool reference = false;
  if (reference_.errors->referenceVersion() != reference_.uploadedVersion) {
    reference_.uploadedVersion = reference_.errors->referenceVersion();
    sides_.setReference(reference_.errors->reference().get());
    reference = true;
  }
  // New points arrive on the render thread; the plot redraws when they do.
  const bool points = convergence_.show && reference_.errors->version() != convergence_.seriesVersion;
  return image || techniques || reference || points || outliers;
}

void Viewer::applySettings() {
  if (sides_.apply(wantedSettings(a()), wantedSettings(b()))) forceRefresh_ = true;
}

void Viewer::syncRenderers() {
  // The technique table that per-technique timing feeds is shown with the convergence panel.
  sides_.sync(run_.userPaused, run_.targetSpp, ui_.showUi && convergence_.show,
              outliers_.on && outlierFinderProblem(estimator_.settings).empty() ? outliers_.count : 0);
}

void Viewer::waitForPyramid(double seconds) {
  if (!pyramid_.show || renderSettings(estimator_).pyramidLength == 0) return;
  techniqueImages_.waitForPyramid(a().renderer(), seconds);
  forceRefresh_ = true;
}

void Viewer::drawImage(Vec2i framebufferSize) {
  b().draw(framebufferSize.y, shownDisplay());
  inspect_.drawRaster(scenes_.scene());
  a().draw(framebufferSize.y, shownDisplay());
}

std::optional<float> Viewer::imageAspect() const {
  // A reference sets the pixels (the error needs the same ones), and with them the shape.
  if (const std::optional<ReferenceView> view = reference_.errors->referenceView(); view && reference_.matchSize)
    return static_cast<float>(view->width) / static_cast<float>(std::max(view->height, 1));
  // The orbit/fly override carries the scene camera's aspect (OrbitCamera keeps it); a preset's
  // camera has none of its own and shows the same scene: it keeps the scene camera's too.
  return cameraAspect(estimator_.settings.camera, scene().cameraDesc());
}

void Viewer::pollSceneLoad() {
  const std::optional<SceneSwitch> change = scenes_.poll();
  if (!change) return;
  // The error against a reference of another scene (or of the file before it was edited) is
  // meaningless: drop it (the plot keeps what was measured against it).
  const bool hadReference = reference_.errors->reference() != nullptr;
  reference_.errors->dropReference();
  if (!change->reload) resetCamera();
  fitEstimatorToCamera();
  sides_.setScene(scenes_.scene(), wantedSettings(a()), wantedSettings(b()));
  forceRefresh_ = true;
  scenes_.announce(*change, hadReference);
}

void Viewer::finishLoading(double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  // Each round takes one finished load; a failed one resets the edit, so this ends.
  while (busy() && std::chrono::steady_clock::now() < end) {
    scenes_.syncEnvironment();
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    pollSceneLoad();
  }
}

void Viewer::resetCamera() {
  scenes_.resetOrbit();
  estimator_.settings.camera.reset();
}

PresetTarget Viewer::presetTarget() {
  return {estimator_, scenes_.orbit(), compare_, scene(), ui_.message};
}

// Over A's image, in place of it, when asked and A runs Metropolis: coloured again whenever A
// publishes (MltSummary comes with every full pass).
void Viewer::drawChainDensity(float fbScale) {
  const RenderSnapshot& snapshot = a().snapshot();
  const MltSummary* mlt = snapshot.mlt.get();
  if (!estimator_.showChainDensity || !a().running() || !mlt || mlt->density.empty()) return;
  if (chainDensity_.version != snapshot.version) {
    uploadDisplayColours(chainDensity_.texture, densityColours(mlt->density, mlt->width, mlt->height));
    chainDensity_.version = snapshot.version;
  }
  drawOverImage(chainDensity_.texture, a().rect, fbScale);
}

}  // namespace pathlab::ui
