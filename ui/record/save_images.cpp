// Ctrl+S: the sides' newest full-resolution images written as EXR and PNG.
#include "ui/record/save_images.h"

#include "core/film/image_io.h"
#include "ui/record/output_names.h"

#include <fmt/core.h>

namespace pathlab::ui {

void saveImages(const RenderLane& sideA, const RenderLane& sideB, float exposure, MessageLine& message) {
  const RenderSnapshot& a = sideA.snapshot();
  if (a.image.width <= 0 || a.preview) {
    message.show("nothing to save yet: wait for the first full-resolution pass", true);
    return;
  }
  try {
    const RenderSnapshot& b = sideB.snapshot();
    const bool both = sideB.running() && b.image.width > 0 && !b.preview;
    const std::string stem = freshStem("out", "pathlab", {".exr", ".png", "-B.exr", "-B.png"});
    writeImage(stem + ".exr", a.image);
    writeImage(stem + ".png", a.image, exposure);
    if (both) {
      // Side B beside it, so each side can be compared with a render of its configuration.
      writeImage(stem + "-B.exr", b.image);
      writeImage(stem + "-B.png", b.image, exposure);
      message.show(fmt::format("saved {}.exr/.png (A, {} spp) and {}-B.exr/.png (B, {} spp)", stem, a.samplesPerPixel,
                               stem, b.samplesPerPixel));
    } else {
      message.show(fmt::format("saved {}.exr and .png ({} spp)", stem, a.samplesPerPixel));
    }
  } catch (const std::exception& e) {
    message.show(e.what(), true);
  }
}

}  // namespace pathlab::ui
