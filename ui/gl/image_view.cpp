// Full-screen-triangle pass over the radiance texture.
#include "ui/gl/image_view.h"

#include "ui/gl/gl.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace pathlab::ui {

ImageView::ImageView() : program_("fullscreen.vert", "display.frag") {
  // A core profile draw needs a bound vertex array even without attributes.
  glGenVertexArrays(1, &vertexArray_);
  glGenFramebuffers(1, &cacheFramebuffer_);
}

ImageView::~ImageView() {
  glDeleteFramebuffers(1, &cacheFramebuffer_);
  glDeleteVertexArrays(1, &vertexArray_);
}

void ImageView::upload(const Image& image, int fullWidth, int fullHeight) {
  if (image.width <= 0 || image.height <= 0) return;
  texture_.uploadRgbFloat(image.width, image.height, image.rgb.data());
  // A preview of factor f is ceil(W / f) wide: its last texel column is partly outside the image.
  const float f = std::max(1.f, std::round(static_cast<float>(fullWidth) / static_cast<float>(image.width)));
  uvScale_ = {std::min(1.f, static_cast<float>(fullWidth) / (f * static_cast<float>(image.width))),
              std::min(1.f, static_cast<float>(fullHeight) / (f * static_cast<float>(image.height)))};
  aspect_ = static_cast<float>(fullWidth) / static_cast<float>(std::max(fullHeight, 1));
  fullSize_ = {fullWidth, fullHeight};
  ++version_;
}

void ImageView::setReference(const Image* reference) {
  if (reference && reference->width > 0) reference_.uploadRgbFloat(reference->width, reference->height, reference->rgb.data());
  else reference_ = Texture();
  ++version_;  // the cached error view is stale
}

void ImageView::renderCache(Vec2i size, const DisplaySettings& display) {
  GLint target = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &target);
  if (cachedSize_ != size) cache_.uploadRgba8(size.x, size.y, nullptr);
  glBindFramebuffer(GL_FRAMEBUFFER, cacheFramebuffer_);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, cache_.id(), 0);
  glViewport(0, 0, size.x, size.y);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_DEPTH_TEST);
  glUseProgram(program_.id());
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_.id());
  glUniform1i(program_.uniform("radiance"), 0);
  glUniform2f(program_.uniform("uvScale"), uvScale_.x, uvScale_.y);
  glUniform1f(program_.uniform("exposureScale"), std::exp2(display.exposure));
  glUniform1i(program_.uniform("toneMap"), display.toneMap == ToneMap::Filmic ? 1 : 0);
  glUniform1i(program_.uniform("falseColour"), display.falseColour ? 1 : 0);
  glUniform1f(program_.uniform("logMin"), display.logMin);
  glUniform1f(program_.uniform("logMax"), display.logMax);
  const bool errorView = display.errorView && !reference_.empty();
  glUniform1i(program_.uniform("errorView"),
              errorView ? (display.errorKind == PixelError::RelativeSquared ? 1 : 2) : 0);
  glUniform1i(program_.uniform("errorLog"), display.errorLog ? 1 : 0);
  glUniform1f(program_.uniform("errorMin"), display.errorLogMin);
  glUniform1f(program_.uniform("errorMax"), display.errorLog ? display.errorLogMax : display.errorLinearMax);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, errorView ? reference_.id() : texture_.id());
  glUniform1i(program_.uniform("reference"), 1);
  glActiveTexture(GL_TEXTURE0);
  glBindVertexArray(vertexArray_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glActiveTexture(GL_TEXTURE1);
  glBindTexture(GL_TEXTURE_2D, 0);
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(target));
  cachedSize_ = size;
  cachedVersion_ = version_;
  cachedDisplay_ = display;
}

PixelRect ImageView::draw(Vec2i origin, Vec2i size, int fbHeight, const DisplaySettings& display) {
  if (empty() || size.x <= 0 || size.y <= 0) return {};
  // Letterbox: while a resize is being rendered the shown image may have another aspect. An image
  // whose shape differs from the rectangle's only by the rounding of one of its sides (the viewer
  // renders the camera's aspect at --render-scale) fills it.
  const long long rounding = std::llabs(static_cast<long long>(fullSize_.x) * size.y - static_cast<long long>(fullSize_.y) * size.x);
  const PixelRect fitted = rounding <= std::max(size.x, size.y) ? PixelRect{origin, size} : fitAspect({origin, size}, aspect_);
  const Vec2i drawSize = fitted.size, drawOrigin = fitted.origin;
  if (drawSize != cachedSize_ || version_ != cachedVersion_ || !(display == cachedDisplay_)) renderCache(drawSize, display);
  const int y0 = fbHeight - drawOrigin.y - drawSize.y;
  GLint read = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, cacheFramebuffer_);
  glBlitFramebuffer(0, 0, drawSize.x, drawSize.y, drawOrigin.x, y0, drawOrigin.x + drawSize.x, y0 + drawSize.y,
                    GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(read));
  return fitted;
}

}  // namespace pathlab::ui
