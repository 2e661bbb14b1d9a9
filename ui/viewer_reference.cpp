// The viewer's reference plumbing: loading one (or taking the shown image), checking that it still
// shows the rendered view, the display the error view gets, and exporting the error series.
#include "ui/viewer.h"

#include "core/film/image_io.h"
#include "ui/record/output_names.h"

#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace pathlab::ui {

void Viewer::loadReference(const std::string& path) {
  try {
    Image reference = readImage(path);
    const RenderSettings current = renderSettings(estimator_);
    if (!reference_.matchSize && (reference.width != current.width || reference.height != current.height))
      throw std::invalid_argument(fmt::format(
          "{} is {} x {} but the image is {} x {}: not loaded (tick \"render at the reference's size\")", path,
          reference.width, reference.height, current.width, current.height));
    const std::string size = fmt::format("{} x {}", reference.width, reference.height);
    reference_.errors->setReference(std::move(reference), viewOf(current, &scene()), path);
    convergence_.show = true;
    showMessage(fmt::format("reference {} ({}): the error is measured from the next pass on", path, size));
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

void Viewer::useImageAsReference() {
  const RenderSnapshot& shown = a().snapshot();
  if (shown.image.width <= 0 || shown.preview) {
    showMessage("nothing to take yet: wait for the first full-resolution pass", true);
    return;
  }
  try {
    // Its own generation is never compared with it: those samples are the reference's.
    reference_.errors->setReference(shown.image, viewOf(shown.settings, &scene()),
                                    fmt::format("the image of generation {} ({} spp, {})", shown.generation,
                                                shown.samplesPerPixel, seriesLabel(shown.settings)),
                                    shown.generation);
    convergence_.show = true;
    showMessage(fmt::format("reference: the current image ({} spp); change the configuration to measure another",
                            shown.samplesPerPixel));
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

void Viewer::returnToReferenceView() {
  const std::optional<ReferenceView> view = reference_.errors->referenceView();
  if (!view) return;
  estimator_.settings.camera = view->camera;
  estimator_.settings.lens = view->lens;
  const Scene& scene = this->scene();
  scenes_.orbit() = OrbitCamera(view->camera.value_or(scene.cameraDesc()), scene.boundsMin(), scene.boundsMax());
}

void Viewer::updateReferenceState() {
  ErrorTracker& errors = *reference_.errors;
  std::string why;
  const ReferenceStatus status = errors.statusFor(renderSettings(estimator_), &scene(), &why);
  reference_.status = status == ReferenceStatus::Valid || status == ReferenceStatus::None ? std::string() : why;
  if (static_cast<int>(errors.maxSeries()) != convergence_.maxSeries)
    errors.setMaxSeries(static_cast<size_t>(convergence_.maxSeries));
  if (const uint64_t v = errors.version(); v != convergence_.seriesVersion) {
    convergence_.series = errors.series();
    convergence_.seriesVersion = v;
  }
}

DisplaySettings Viewer::shownDisplay() const {
  DisplaySettings d = display_;
  // The shown image (a preview included) must be of the reference's view, else its colours lie.
  d.errorView = display_.errorView &&
                reference_.errors->statusFor(a().snapshot().settings, &scene()) == ReferenceStatus::Valid;
  return d;
}

std::string Viewer::errorViewProblem() const {
  if (!display_.errorView || shownDisplay().errorView) return {};
  if (!reference_.status.empty()) return reference_.status;
  return reference_.errors->reference() ? "waiting for an image of the reference's view"
                                        : "no reference (load one, or Ctrl+R)";
}

void Viewer::writeErrorCsv(const std::string& path, bool force) const {
  if (!force && std::filesystem::exists(path)) throw std::runtime_error(path + ": file exists (pass --force to overwrite it)");
  const std::filesystem::path p(path);
  if (!p.parent_path().empty() && !std::filesystem::is_directory(p.parent_path()))
    throw std::runtime_error(path + ": the directory " + p.parent_path().string() + " does not exist");
  const std::string temporary = path + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary);
    out << reference_.errors->csv();
    if (!out) throw std::runtime_error(path + ": cannot write");
  }
  std::filesystem::rename(temporary, path);
}

void Viewer::exportErrorCsv() {
  try {
    const std::string path = freshStem("out", "pathlab-error", {".csv"}) + ".csv";
    writeErrorCsv(path, false);
    showMessage("saved the error series as " + path);
  } catch (const std::exception& e) {
    showMessage(e.what(), true);
  }
}

}  // namespace pathlab::ui
