// Image files read through tinyexr and stb_image, plus a hand-written PFM reader (image_read.h).
#include "core/image/image_read.h"

#include <stb/stb_image.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace pathlab {

namespace fs = std::filesystem;

ImageFormat imageFormatOf(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".exr") return ImageFormat::Exr;
  if (ext == ".pfm") return ImageFormat::Pfm;
  if (ext == ".png") return ImageFormat::Png;
  throw ImageError(path + ": unknown image format '" + ext + "' (use .exr, .pfm or .png)");
}

namespace {

Image readPfm(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw ImageError(path + ": cannot open");
  std::string magic;
  Image img;
  float scale = 0.f;
  f >> magic >> img.width >> img.height >> scale;
  f.get();
  if (!f || magic != "PF" || img.width <= 0 || img.height <= 0 || img.width > 65536 || img.height > 65536)
    throw ImageError(path + ": not a colour PFM file");
  if (scale > 0.f) throw ImageError(path + ": big-endian PFM is not supported");
  img.rgb.resize(3 * static_cast<size_t>(img.width) * static_cast<size_t>(img.height));
  for (int y = img.height - 1; y >= 0; --y)  // PFM stores rows bottom-up
    f.read(reinterpret_cast<char*>(&img.rgb[3 * static_cast<size_t>(y) * static_cast<size_t>(img.width)]),
           static_cast<std::streamsize>(3 * sizeof(float) * static_cast<size_t>(img.width)));
  if (!f) throw ImageError(path + ": truncated PFM data");
  return img;
}

Image readExr(const std::string& path) {
  float* rgba = nullptr;
  int w = 0, h = 0;
  const char* err = nullptr;
  if (LoadEXR(&rgba, &w, &h, path.c_str(), &err) != TINYEXR_SUCCESS) {
    std::string msg = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw ImageError(path + ": cannot read EXR: " + msg);
  }
  Image img{w, h, std::vector<float>(3 * static_cast<size_t>(w) * static_cast<size_t>(h))};
  for (size_t i = 0; i < static_cast<size_t>(w) * static_cast<size_t>(h); ++i)
    for (size_t c = 0; c < 3; ++c) img.rgb[3 * i + c] = rgba[4 * i + c];
  free(rgba);
  return img;
}

}  // namespace

Image readImage(const std::string& path) {
  if (!fs::exists(path)) throw ImageError(path + ": no such file");
  switch (imageFormatOf(path)) {
    case ImageFormat::Exr: return readExr(path);
    case ImageFormat::Pfm: return readPfm(path);
    case ImageFormat::Png: break;
  }
  throw ImageError(path + ": reading PNG is not supported (use .exr or .pfm)");
}

Image readRadianceHdr(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  float* data = stbi_loadf(path.c_str(), &w, &h, &channels, 3);
  if (!data) {
    const char* why = stbi_failure_reason();
    throw ImageError(path + ": cannot read the HDR image (" + (why ? why : "unknown error") + ")");
  }
  Image img{w, h, std::vector<float>(data, data + 3 * static_cast<size_t>(w) * static_cast<size_t>(h))};
  stbi_image_free(data);
  return img;
}

}  // namespace pathlab
