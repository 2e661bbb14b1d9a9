// Reading images from files: .exr (through tinyexr), .pfm and Radiance .hdr (hand-written). Every file
// through core/io/guarded_file.h, every claimed size checked against the file's length and
// kMaxImageTexels before allocating (image_budget.h). Below the film and the lights, which both read.
#pragma once

#include "core/image/image.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace pathlab {

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ImageFormat { Exr, Pfm, Png };

// From the file extension (case-insensitive); throws ImageError naming the path otherwise.
ImageFormat imageFormatOf(const std::string& path);

// Each throws ImageError with one line naming the file (or `name`): unreadable, special or too
// large files, truncated data, headers that claim more than the file holds or the budget allows.
Image readImage(const std::string& path);  // .exr or .pfm

// A Radiance RGBE (.hdr) file, flat or run-length encoded, as linear floats.
Image readRadianceHdr(const std::string& path);

// The decoders alone, on a file's bytes (the fuzz targets call these); `name` starts the messages.
Image decodeImage(const std::vector<unsigned char>& bytes, ImageFormat format, const std::string& name);
Image decodeRadianceHdr(const std::vector<unsigned char>& bytes, const std::string& name);

}  // namespace pathlab
