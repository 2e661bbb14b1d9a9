// Writing images: .exr (32-bit float), .pfm (float) and .png (tone mapped, sRGB); reading them is
// core/image/image_read.h's, included here for the callers that do both.
#pragma once

#include "core/film/film.h"
#include "core/image/image_read.h"

#include <string>
#include <vector>

namespace pathlab {

// Writes atomically (a temporary file beside the target, then rename), so an interrupted write
// never leaves a half-written image in place of a good one. Float formats store the linear
// radiance; `exposure` (stops) applies to PNG only, which is clamped and sRGB-encoded.
void writeImage(const std::string& path, const Image& image, float exposure = 0.f);

// Display value in [0,1] of one linear channel: exposure (stops), clamp, sRGB encode.
float exposeToSrgb(float linear, float exposure);

// The 8-bit sRGB bytes a PNG gets, RGB row-major top-first.
std::vector<unsigned char> toneMapSrgb8(const Image& image, float exposure);

}  // namespace pathlab
