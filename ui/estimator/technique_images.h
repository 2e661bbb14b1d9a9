// Side A's per-technique images as textures: the pyramid's thumbnails (tone mapped as the panel
// asks) and the technique map shown over the image, taken from A's renderer at a bounded rate.
#pragma once

#include "ui/display/image_rect.h"
#include "ui/viewer_state.h"

namespace pathlab::ui {

// Uploads display colours (sRGB values in [0, 1], core/maps/map_colours.h) into `texture`.
void uploadDisplayColours(Texture& texture, const Image& colours);
// Draws `texture` over `image` (framebuffer pixels) in ImGui's background, fitted into it like the
// image (ImageView::draw) and centred: a texture of the image's aspect covers it exactly.
void drawOverImage(const Texture& texture, const PixelRect& image, float framebufferScale);

class TechniqueImages {
 public:
  PyramidImages pyramid;
  MapImages maps;

  // A new renderer counts its versions from the start again.
  void restart() {
    pyramid.version = 0;
    maps.version = 0;
  }
  // Takes what is due (or everything, `force`) of what is shown; true when a texture changed.
  bool update(ProgressiveRenderer& renderer, const PyramidView& pyramidView, const MapView& mapView,
              const DisplaySettings& display, bool force);
  // The chosen map over `image` (framebuffer pixels), when shown and arrived (ImGui's background).
  void drawMap(const MapView& mapView, const PixelRect& image, float framebufferScale) const;
  // Waits (up to `seconds`) until the renderer publishes the thumbnails of its newest pass.
  void waitForPyramid(ProgressiveRenderer& renderer, double seconds) const;

 private:
  bool updatePyramid(ProgressiveRenderer& renderer, const PyramidView& view, const DisplaySettings& display, bool due);
  bool updateMaps(ProgressiveRenderer& renderer, const MapView& view, bool due);
};

}  // namespace pathlab::ui
