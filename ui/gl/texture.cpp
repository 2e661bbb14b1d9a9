// OpenGL texture upload. Nearest filtering: previews are scaled up blocky on purpose (each block
// is one sample), and the full image is shown one texel per pixel.
#include "ui/gl/texture.h"

#include "ui/gl/gl.h"

#include <utility>

namespace pathlab::ui {

Texture::Texture() {
  glGenTextures(1, &id_);
  glBindTexture(GL_TEXTURE_2D, id_);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

Texture::~Texture() {
  if (id_) glDeleteTextures(1, &id_);
}

Texture::Texture(Texture&& o) noexcept
    : id_(std::exchange(o.id_, 0)), width_(o.width_), height_(o.height_), internalFormat_(o.internalFormat_) {}

Texture& Texture::operator=(Texture&& o) noexcept {
  std::swap(id_, o.id_);
  std::swap(width_, o.width_);
  std::swap(height_, o.height_);
  std::swap(internalFormat_, o.internalFormat_);
  return *this;
}

void Texture::upload(int width, int height, int internalFormat, unsigned format, unsigned type, const void* data) {
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  if (width != width_ || height != height_ || internalFormat != internalFormat_) {
    glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, width, height, 0, format, type, data);
    width_ = width;
    height_ = height;
    internalFormat_ = internalFormat;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, format, type, data);
  }
}

void Texture::uploadRgbFloat(int width, int height, const float* rgb) {
  upload(width, height, GL_RGB32F, GL_RGB, GL_FLOAT, rgb);
}

void Texture::uploadRgba8(int width, int height, const uint8_t* rgba) {
  upload(width, height, GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, rgba);
}

}  // namespace pathlab::ui
