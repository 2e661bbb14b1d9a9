// Framebuffer read-back and PNG writing for screenshots.
#include "ui/gl/screenshot.h"

#include "ui/gl/gl.h"

#include <stb/stb_image_write.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <unistd.h>

namespace pathlab::ui {

std::vector<unsigned char> readFramebufferRgba(Vec2i size) { return readFramebufferRgba(size, Vec2i(0), size); }

std::vector<unsigned char> readFramebufferRgba(Vec2i framebufferSize, Vec2i origin, Vec2i size) {
  std::vector<unsigned char> rows(static_cast<size_t>(size.x) * static_cast<size_t>(size.y) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(origin.x, framebufferSize.y - origin.y - size.y, size.x, size.y, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
  // GL rows come bottom-up.
  std::vector<unsigned char> out(rows.size());
  const size_t stride = static_cast<size_t>(size.x) * 4;
  for (size_t y = 0; y < static_cast<size_t>(size.y); ++y)
    std::copy_n(rows.data() + (static_cast<size_t>(size.y) - 1 - y) * stride, stride, out.data() + y * stride);
  return out;
}

void writePngRgba(const std::string& path, Vec2i size, const std::vector<unsigned char>& rgba) {
  std::vector<unsigned char> rgb(static_cast<size_t>(size.x) * static_cast<size_t>(size.y) * 3);
  for (size_t p = 0; p < rgb.size() / 3; ++p)
    for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = rgba[4 * p + c];
  const std::string tmp = path + ".tmp-" + std::to_string(getpid()) + ".png";
  if (!stbi_write_png(tmp.c_str(), size.x, size.y, 3, rgb.data(), size.x * 3)) {
    std::filesystem::remove(tmp);
    throw std::runtime_error(path + ": cannot write the PNG");
  }
  std::filesystem::rename(tmp, path);
}

}  // namespace pathlab::ui
