// The viewer's plumbing: settings to the renderer, snapshots to the texture, scenes, presets, saving.
#include "ui/viewer.h"

#include "core/film/image_io.h"
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

double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

Viewer::Viewer(const ViewerOptions& options, std::shared_ptr<const Scene> scene, std::vector<NamedPreset> presets)
    : scene_(std::move(scene)),
      scenePath_(options.scene),
      edited_(options.settings),
      targetSpp_(options.spp),
      presets_(std::move(presets)),
      presetsPath_(options.presetsFile),
      imageView_(std::make_unique<ImageView>()),
      errors_(std::make_shared<ErrorTracker>()),
      showUi_(!options.hideUi) {
  display_.exposure = options.exposure;
  resolutionScale_ = options.renderScale;
  if (options.pyramidLength > 0) {
    showPyramid_ = true;
    pyramidLength_ = options.pyramidLength;
  }
  if (edited_.isolate) isolateS_ = edited_.isolate->s, isolateT_ = edited_.isolate->t;
  oneLength_ = std::min(oneLength_, edited_.maxLength);
  orbit_ = OrbitCamera(scene_->cameraDesc(), scene_->boundsMin(), scene_->boundsMax());
  if (!options.preset.empty())
    for (size_t i = 0; i < presets_.size(); ++i)
      if (presets_[i].name == options.preset) currentPreset_ = static_cast<int>(i);
  if (edited_.camera) {
    // A preset's camera: orbit from there.
    orbit_ = OrbitCamera(*edited_.camera, scene_->boundsMin(), scene_->boundsMax());
  }
  applied_ = effectiveSettings(edited_);
  // The first frame sets the real image size; start small so nothing big is rendered in vain.
  applied_.width = applied_.height = 64;
  RenderSettings initial = applied_;
  if (noTechniqueEnabled(initial)) initial.techniques = TechniqueSet::all();
  if (!options.reference.empty()) {
    // From the command line a bad reference is an error of the command, not a message.
    errors_->setReference(readImage(options.reference), viewOf(effectiveSettings(edited_), scene_.get()),
                          options.reference);
    showConvergence_ = true;
  }
  showConvergence_ = showConvergence_ || options.convergencePanel;
  display_.errorView = options.errorView;
  renderer_ = std::make_unique<ProgressiveRenderer>(scene_, initial, options.threads);
  renderer_->setTargetSpp(targetSpp_);
  // Errors are measured on the render thread after each full pass (no copy of the image, no wait
  // for the UI's refresh); the tracker outlives the renderer through this shared pointer.
  renderer_->setPassObserver([errors = errors_](const PassInfo& info, const Image& mean) { errors->observe(info, mean); });
  refreshSceneFiles();
}

Viewer::~Viewer() = default;  // the renderer cancels its pass and joins its worker

void Viewer::showMessage(const std::string& text, bool error) {
  message_ = text;
  messageIsError_ = error;
  messageTime_ = std::chrono::steady_clock::now();
}

void Viewer::buildFrame(Vec2i framebufferSize, float framebufferScale, const std::vector<std::string>& droppedPaths) {
  ImGuiIO& io = ImGui::GetIO();
  for (const std::string& path : droppedPaths) openScene(path);
  pollSceneLoad();

  handleShortcuts();
  // Panels beside the image, never over it: the controls on the left, the pyramid on the right,
  // the convergence plot and technique table along the bottom.
  const float bottom = showUi_ && showConvergence_ ? convergencePanelHeight(io.DisplaySize.y) : 0.f;
  const float upper = io.DisplaySize.y - bottom;
  const float panelWidth = showUi_ ? std::min(380.f * uiScale_, io.DisplaySize.x * 0.6f) : 0.f;
  const float pyramidWidth = showUi_ && showPyramid_ ? pyramidPanelWidth(io.DisplaySize.x - panelWidth, upper) : 0.f;
  imageOrigin_ = {static_cast<int>(panelWidth * framebufferScale), 0};
  imageSize_ = {std::max(framebufferSize.x - imageOrigin_.x - static_cast<int>(pyramidWidth * framebufferScale), 0),
                std::max(framebufferSize.y - static_cast<int>(bottom * framebufferScale), 0)};
  handleCamera(framebufferScale);
  updateReferenceState();

  if (showUi_) {
    drawSidePanel(panelWidth, upper);
    if (showPyramid_) drawPyramidWindow(io.DisplaySize.x - pyramidWidth, pyramidWidth, upper);
    if (showConvergence_) drawConvergenceWindow(upper, io.DisplaySize.x, bottom);
  }
  if (showHelp_) drawHelpWindow();
  drawImageOverlay();

  // The image follows its area of the window (a resize is a new generation, like any other change).
  // ... unless a reference sets it: an error needs the same pixels.
  if (const std::optional<ReferenceView> view = errors_->referenceView(); view && matchReferenceSize_) {
    edited_.width = view->width;
    edited_.height = view->height;
  } else {
    edited_.width = std::max(1, static_cast<int>(static_cast<float>(imageSize_.x) * resolutionScale_));
    edited_.height = std::max(1, static_cast<int>(static_cast<float>(imageSize_.y) * resolutionScale_));
  }
  // Per-technique timing costs two clock reads a connection: only while its table is shown.
  const bool timing = showUi_ && showConvergence_;
  if (timing != timingOn_) renderer_->setTiming(timingOn_ = timing);
  edited_.pyramidLength = showPyramid_ ? std::min(pyramidLength_, edited_.maxLength) : 0;
  if (showPyramid_) {
    // Thumbnails as large as they are shown (no blocky upscaling on a projector), from the next pass.
    const int side = std::clamp(static_cast<int>(std::max(pyramidThumbnail_.x, pyramidThumbnail_.y) * framebufferScale), 32, 256);
    if (side != thumbnailSide_) renderer_->setThumbnailSide(thumbnailSide_ = side);
  }
  if (imageSize_.x > 0 && imageSize_.y > 0) applySettings();  // a minimised window keeps rendering the old size
}

bool Viewer::pollImage() {
  if (secondsSince(lastPriorityCheck_) > 1.0) {
    // New TBB workers appear lazily; they inherit nothing from the UI's wishes.
    lowerRenderThreadPriority(kRenderThreadNice);
    lastPriorityCheck_ = std::chrono::steady_clock::now();
  }
  const bool pyramid = showPyramid_ && updatePyramid();
  const bool image = updateImage();
  bool reference = false;
  if (errors_->referenceVersion() != uploadedReference_) {
    uploadedReference_ = errors_->referenceVersion();
    const std::shared_ptr<const Image> r = errors_->reference();
    imageView_->setReference(r.get());
    reference = true;
  }
  // New points arrive on the render thread; the plot redraws when they do.
  const bool points = showConvergence_ && errors_->version() != seriesVersion_;
  return image || pyramid || reference || points;
}

void Viewer::applySettings() {
  // The renderer cannot run an empty technique set: idle and show black until one is enabled.
  const bool nothing = noTechniqueEnabled(edited_);
  if (nothing != idleForNoTechnique_) {
    idleForNoTechnique_ = nothing;
    renderer_->setPaused(nothing || userPaused_);
  }
  const RenderSettings wanted = effectiveSettings(edited_);
  if (nothing || wanted == applied_) return;
  applied_ = wanted;
  try {
    renderer_->setSettings(wanted);
    settingsError_.clear();
    forceRefresh_ = true;
  } catch (const std::exception& e) {
    // The renderer keeps its previous settings; the panel shows why until the next change.
    settingsError_ = e.what();
  }
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
  const bool due = forceRefresh_ || secondsSince(lastPyramidPoll_) >= kPyramidRefreshSeconds;
  if (due) lastPyramidPoll_ = std::chrono::steady_clock::now();
  const bool fresh = due && renderer_->pyramid(thumbnails_, pyramidVersion_);
  // Re-tone the thumbnails we have when their display changes (exposure mode, tone map, ...).
  const bool retone = !(thumbnailDisplay_ == display_) || thumbnailOwnExposure_ != pyramidOwnExposure_;
  if (!fresh && !retone) return false;
  thumbnailDisplay_ = display_;
  thumbnailOwnExposure_ = pyramidOwnExposure_;
  thumbnailTextures_.resize(2 * thumbnails_.size());
  for (size_t i = 0; i < thumbnails_.size(); ++i) {
    const Image* images[2] = {&thumbnails_[i].weighted, &thumbnails_[i].unweighted};
    for (int u = 0; u < 2; ++u) {
      if (images[u]->width <= 0) continue;
      // Own exposure: every technique visible although their magnitudes differ by orders of
      // magnitude. Common exposure (the image's): the weighted shares compare directly.
      DisplaySettings d = display_;
      if (pyramidOwnExposure_) d.exposure = autoExposure(*images[u]);
      const std::vector<uint8_t> rgba = toRgba8(*images[u], d);
      thumbnailTextures_[2 * i + static_cast<size_t>(u)].uploadRgba8(images[u]->width, images[u]->height, rgba.data());
    }
  }
  return true;
}

void Viewer::waitForPyramid(double seconds) {
  if (!showPyramid_ || effectiveSettings(edited_).pyramidLength == 0) return;
  const auto start = std::chrono::steady_clock::now();
  std::vector<TechniqueThumbnail> probe;
  uint64_t version = pyramidVersion_;
  // The renderer publishes the thumbnails of a pass just after its image.
  while (secondsSince(start) < seconds) {
    if (renderer_->pyramid(probe, version) && !probe.empty()) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  forceRefresh_ = true;
}

void Viewer::drawImage(Vec2i framebufferSize) {
  if (idleForNoTechnique_) return;  // black: nothing is estimated
  imageView_->draw(imageOrigin_, imageSize_, framebufferSize.y, shownDisplay());
}

void Viewer::openScene(const std::string& path) {
  loader_.start(path);
  showMessage("loading " + path + " ...");
}

void Viewer::pollSceneLoad() {
  std::optional<SceneLoadResult> r = loader_.poll();
  if (!r) return;
  if (!r->scene) {
    showMessage(r->error + " (the previous scene is kept)", true);
    return;
  }
  // A reload keeps the view (the file is being edited); another scene starts at its own camera.
  const bool reload = r->path == scenePath_;
  // The error against a reference of another scene (or of the file before it was edited) is
  // meaningless: drop it (the plot keeps what was measured against it).
  const bool hadReference = errors_->reference() != nullptr;
  errors_->dropReference();
  scene_ = r->scene;
  scenePath_ = r->path;
  if (!reload) {
    orbit_ = OrbitCamera(scene_->cameraDesc(), scene_->boundsMin(), scene_->boundsMax());
    edited_.camera.reset();
  }
  applied_ = effectiveSettings(edited_);
  if (noTechniqueEnabled(applied_)) applied_.techniques = TechniqueSet::all();
  try {
    renderer_->setScene(scene_, applied_);
    settingsError_.clear();
  } catch (const std::exception& e) {
    settingsError_ = e.what();
  }
  forceRefresh_ = true;
  refreshSceneFiles();
  std::string text = fmt::format("loaded {}: {} triangles, {} lights", scenePath_, scene_->triangleCount(),
                                 scene_->lights().size());
  for (const std::string& w : scene_->warnings()) text += "; warning: " + w;
  if (hadReference) text += "; the reference was dropped (it showed the previous scene)";
  showMessage(text);
}

void Viewer::refreshSceneFiles() {
  sceneFiles_.clear();
  std::vector<std::filesystem::path> dirs = {std::filesystem::path(scenePath_).parent_path(), PATHLAB_ASSETS_DIR};
  for (const auto& dir : dirs) {
    std::error_code ec;
    if (dir.empty() || !std::filesystem::is_directory(dir, ec)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".gltf" && ext != ".glb") continue;
      std::string p = std::filesystem::relative(entry.path(), ec).string();
      if (ec || p.empty() || p.starts_with("../../")) p = entry.path().string();
      if (std::find(sceneFiles_.begin(), sceneFiles_.end(), p) == sceneFiles_.end()) sceneFiles_.push_back(p);
    }
  }
  std::sort(sceneFiles_.begin(), sceneFiles_.end());
}

void Viewer::resetCamera() {
  orbit_ = OrbitCamera(scene_->cameraDesc(), scene_->boundsMin(), scene_->boundsMax());
  edited_.camera.reset();
}

void Viewer::applyPreset(int index) {
  if (presets_.empty()) return;
  index = (index % static_cast<int>(presets_.size()) + static_cast<int>(presets_.size())) % static_cast<int>(presets_.size());
  currentPreset_ = index;
  const NamedPreset& p = presets_[static_cast<size_t>(index)];
  edited_ = p.applyTo(edited_);
  if (p.camera) orbit_ = OrbitCamera(*p.camera, scene_->boundsMin(), scene_->boundsMax());
  if (p.isolate) isolateS_ = p.isolate->s, isolateT_ = p.isolate->t;
  oneLength_ = std::min(oneLength_, edited_.maxLength);
  showMessage("preset: " + p.name);
}

void Viewer::saveImage() {
  if (snapshot_.image.width <= 0 || snapshot_.preview) {
    showMessage("nothing to save yet: wait for the first full-resolution pass", true);
    return;
  }
  try {
    const std::string stem = freshStem("out", "pathlab", {".exr", ".png"});
    writeImage(stem + ".exr", snapshot_.image);
    writeImage(stem + ".png", snapshot_.image, display_.exposure);
    showMessage(fmt::format("saved {}.exr and .png ({} spp)", stem, snapshot_.samplesPerPixel));
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

}  // namespace pathlab::ui
