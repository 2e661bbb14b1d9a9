// A side of the shown image: its renderer started, fed settings, synced, polled and drawn.
#include "ui/lane/render_lane.h"

#include "ui/estimator/technique_grid.h"

namespace pathlab::ui {

namespace {

// Full-resolution images are shown at most this often: uploading and drawing a float frame costs
// llvmpipe several milliseconds of CPU that the render threads would otherwise get. Previews and
// the first image of a generation are shown at once.
constexpr double kImageRefreshSeconds = 0.25;

// The renderer cannot run an empty technique set: it gets all of them and idles (the lane shows
// black) until one is enabled.
RenderSettings runnable(RenderSettings s) {
  if (noTechniqueEnabled(s)) s.techniques = TechniqueSet::all();
  return s;
}

}  // namespace

void RenderLane::observe(const std::shared_ptr<ErrorTracker>& errors) {
  // Errors are measured on the render thread after each full pass (no copy of the image, no wait
  // for the UI's refresh); the tracker outlives the renderer through this shared pointer.
  renderer_->setPassObserver(
      [errors, series = series_](const PassInfo& info, const Image& mean) { errors->observe(info, mean, series); });
}

void RenderLane::start(const std::shared_ptr<const Scene>& scene, const RenderSettings& settings, const LaneStart& how) {
  renderer_.reset();
  applied_ = runnable(settings);
  renderer_ = std::make_unique<ProgressiveRenderer>(scene, applied_, how.threads);
  renderer_->setTargetSpp(how.targetSpp);
  renderer_->setThumbnailSide(how.thumbnailSide);
  observe(how.errors);
  pausedApplied_ = timingApplied_ = false;
  outliersApplied_ = 0;
  targetApplied_ = how.targetSpp;
  // The new renderer counts generations and versions from the start again.
  snapshot_ = RenderSnapshot{};
  if (!view_) view_ = std::make_unique<ImageView>();
}

bool RenderLane::apply(const RenderSettings& wanted) {
  idle_ = noTechniqueEnabled(wanted);
  if (idle_ || wanted == applied_) return false;
  applied_ = wanted;
  try {
    renderer_->setSettings(wanted);
    refused_.clear();
    return true;
  } catch (const std::exception& e) {
    // The renderer keeps its previous settings; the panel shows why until the next change.
    refused_ = e.what();
    return false;
  }
}

void RenderLane::setScene(const std::shared_ptr<const Scene>& scene, const RenderSettings& settings) {
  applied_ = runnable(settings);
  try {
    renderer_->setScene(scene, applied_);
    refused_.clear();
  } catch (const std::exception& e) {
    refused_ = e.what();
  }
}

void RenderLane::sync(bool userPaused, uint64_t targetSpp, bool timing, int outliers) {
  const bool paused = userPaused || idle_;
  if (paused != pausedApplied_) renderer_->setPaused(pausedApplied_ = paused);
  if (targetSpp != targetApplied_) renderer_->setTargetSpp(targetApplied_ = targetSpp);
  // Per-technique timing costs two clock reads a connection: only while its table is shown.
  if (timing != timingApplied_) renderer_->setTiming(timingApplied_ = timing);
  // The outlier finder sends every sample down the recording route: only while its list is shown.
  if (outliers != outliersApplied_) renderer_->setOutlierCount(outliersApplied_ = outliers);
}

bool RenderLane::poll(bool force) {
  if (!renderer_) return false;
  const bool newGeneration = renderer_->generation() != snapshot_.generation;
  const double sincePoll = std::chrono::duration<double>(std::chrono::steady_clock::now() - lastPoll_).count();
  if (!force && !newGeneration && !snapshot_.preview && sincePoll < kImageRefreshSeconds) return false;
  lastPoll_ = std::chrono::steady_clock::now();
  if (!renderer_->snapshot(snapshot_)) return false;
  view_->upload(snapshot_.image, snapshot_.settings.width, snapshot_.settings.height);
  return true;
}

void RenderLane::draw(int framebufferHeight, const DisplaySettings& display) {
  drawn_ = {};
  if (!renderer_ || idle_) return;  // black: nothing is estimated
  drawn_ = view_->draw(rect.origin, rect.size, framebufferHeight, display);
}

void swapRenderers(RenderLane& a, RenderLane& b, const std::shared_ptr<ErrorTracker>& errors) {
  std::swap(a.renderer_, b.renderer_);
  std::swap(a.applied_, b.applied_);
  std::swap(a.refused_, b.refused_);
  std::swap(a.idle_, b.idle_);
  std::swap(a.pausedApplied_, b.pausedApplied_);
  std::swap(a.timingApplied_, b.timingApplied_);
  std::swap(a.outliersApplied_, b.outliersApplied_);
  std::swap(a.targetApplied_, b.targetApplied_);
  std::swap(a.view_, b.view_);
  std::swap(a.snapshot_, b.snapshot_);
  std::swap(a.lastPoll_, b.lastPoll_);
  if (a.renderer_) a.observe(errors);
  if (b.renderer_) b.observe(errors);
}

}  // namespace pathlab::ui
