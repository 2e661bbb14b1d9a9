// Screenshots of the whole viewer (panels included): read back the framebuffer, write a PNG.
#pragma once

#include "core/math/types.h"

#include <string>
#include <vector>

namespace pathlab::ui {

// The pixels of the bound framebuffer, RGBA8, top row first.
std::vector<unsigned char> readFramebufferRgba(Vec2i size);
// The pixels of a rectangle of the bound framebuffer (origin from the top left, as the viewer's
// image area), RGBA8, top row first.
std::vector<unsigned char> readFramebufferRgba(Vec2i framebufferSize, Vec2i origin, Vec2i size);

// Writes RGBA8 (top row first) as an RGB PNG atomically (temporary file, then rename). Throws
// std::runtime_error naming the path on failure.
void writePngRgba(const std::string& path, Vec2i size, const std::vector<unsigned char>& rgba);

}  // namespace pathlab::ui
