// An OpenGL 2D texture owned by the viewer: the float radiance image, or RGBA8 thumbnails.
#pragma once

#include <cstdint>
#include <vector>

namespace pathlab::ui {

class Texture {
 public:
  Texture();
  ~Texture();
  Texture(const Texture&) = delete;
  Texture& operator=(const Texture&) = delete;
  Texture(Texture&& other) noexcept;
  Texture& operator=(Texture&& other) noexcept;

  // Linear radiance, 3 floats a pixel, top row first. Reallocates only when the size changes.
  void uploadRgbFloat(int width, int height, const float* rgb);
  void uploadRgba8(int width, int height, const uint8_t* rgba);

  unsigned id() const { return id_; }
  int width() const { return width_; }
  int height() const { return height_; }
  bool empty() const { return width_ == 0; }
  // For ImGui::Image.
  void* imguiId() const { return reinterpret_cast<void*>(static_cast<uintptr_t>(id_)); }

 private:
  unsigned id_ = 0;
  int width_ = 0, height_ = 0;
  int internalFormat_ = 0;
  void upload(int width, int height, int internalFormat, unsigned format, unsigned type, const void* data);
};

}  // namespace pathlab::ui
