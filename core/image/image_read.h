// Reading images from files: .exr (through tinyexr), .pfm (hand-written) and Radiance .hdr (through
// stb_image). Below the film and the lights, which both read (film/image_io.h also writes).
#pragma once

#include "core/image/image.h"

#include <stdexcept>
#include <string>

namespace pathlab {

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ImageFormat { Exr, Pfm, Png };

// From the file extension (case-insensitive); throws ImageError naming the path otherwise.
ImageFormat imageFormatOf(const std::string& path);

Image readImage(const std::string& path);  // .exr or .pfm

// A Radiance RGBE (.hdr) file, as linear floats.
Image readRadianceHdr(const std::string& path);

}  // namespace pathlab
