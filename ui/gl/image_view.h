// Draws the radiance image through the display transform (shaders/display.frag) into a rectangle
// of the framebuffer, keeping the image's aspect. The transform runs only when the image, the
// display settings or the size change; it renders into a cached RGBA8 framebuffer that every other
// frame merely copies (llvmpipe spends tens of nanoseconds a pixel on the shader).
#pragma once

#include "ui/display/display_settings.h"
#include "ui/display/image_rect.h"
#include "ui/gl/shader_program.h"
#include "ui/gl/texture.h"

#include "core/film/film.h"

namespace pathlab::ui {

class ImageView {
 public:
  ImageView();
  ~ImageView();
  ImageView(const ImageView&) = delete;
  ImageView& operator=(const ImageView&) = delete;

  // `fullWidth` x `fullHeight` is the resolution the image stands for: a preview is smaller and
  // is scaled up with nearest filtering.
  void upload(const Image& image, int fullWidth, int fullHeight);
  bool empty() const { return texture_.empty(); }
  // The reference of the error view (DisplaySettings::errorView), full resolution; null: none.
  void setReference(const Image* reference);
  bool hasReference() const { return !reference_.empty(); }
  // Rectangle in framebuffer pixels, origin top-left (as ImGui's), framebuffer height fbHeight.
  // Returns where the image went (empty: nothing to draw).
  PixelRect draw(Vec2i origin, Vec2i size, int fbHeight, const DisplaySettings& display);

 private:
  ShaderProgram program_;
  Texture texture_;
  Texture reference_;
  unsigned vertexArray_ = 0;
  Vec2 uvScale_{1.f};
  float aspect_ = 1.f;
  Vec2i fullSize_{1};
  // The cache: display transform of image `version_` with `cachedDisplay_` at `cachedSize_`.
  uint64_t version_ = 0, cachedVersion_ = 0;
  DisplaySettings cachedDisplay_;
  Vec2i cachedSize_{0};
  unsigned cacheFramebuffer_ = 0;
  Texture cache_;
  void renderCache(Vec2i size, const DisplaySettings& display);
};

}  // namespace pathlab::ui
