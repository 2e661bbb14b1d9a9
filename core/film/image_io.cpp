// Image files written through tinyexr and stb_image_write, plus a hand-written PFM writer.
#include "core/film/image_io.h"

#include "core/texture/texture.h"

#include <stb/stb_image_write.h>
#include <tinyexr.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace pathlab {

namespace fs = std::filesystem;

float exposeToSrgb(float linear, float exposure) {
  const float v = linear * std::exp2(exposure);
  return linearToSrgb(std::isfinite(v) ? glm::clamp(v, 0.f, 1.f) : 0.f);
}

std::vector<unsigned char> toneMapSrgb8(const Image& image, float exposure) {
  std::vector<unsigned char> out(image.rgb.size());
  for (size_t i = 0; i < image.rgb.size(); ++i)
    out[i] = static_cast<unsigned char>(glm::clamp(exposeToSrgb(image.rgb[i], exposure) * 255.f + 0.5f, 0.f, 255.f));
  return out;
}

namespace {

void writePfm(const std::string& file, const std::string& path, const Image& image) {
  std::ofstream f(file, std::ios::binary);
  if (!f) throw ImageError(path + ": cannot open for writing");
  f << "PF\n" << image.width << " " << image.height << "\n-1.0\n";  // negative scale: little endian
  for (int y = image.height - 1; y >= 0; --y)                     // PFM stores rows bottom-up
    f.write(reinterpret_cast<const char*>(&image.rgb[3 * static_cast<size_t>(y) * static_cast<size_t>(image.width)]),
            static_cast<std::streamsize>(3 * sizeof(float) * static_cast<size_t>(image.width)));
  if (!f) throw ImageError(path + ": write failed");
}

void writeExr(const std::string& file, const std::string& path, const Image& image) {
  const char* err = nullptr;
  if (SaveEXR(image.rgb.data(), image.width, image.height, 3, /*save_as_fp16=*/0, file.c_str(), &err) != TINYEXR_SUCCESS) {
    std::string msg = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    throw ImageError(path + ": cannot write EXR: " + msg);
  }
}

}  // namespace

void writeImage(const std::string& path, const Image& image, float exposure) {
  const ImageFormat format = imageFormatOf(path);
  const fs::path target(path);
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  if (!fs::is_directory(dir)) throw ImageError(path + ": the directory " + dir.string() + " does not exist");
  if (image.width <= 0 || image.height <= 0 || image.rgb.size() != 3 * static_cast<size_t>(image.width) * static_cast<size_t>(image.height))
    throw ImageError(path + ": invalid image size");
  const fs::path tmp = dir / ("." + target.filename().string() + ".tmp" + std::to_string(getpid()));
  try {
    switch (format) {
      case ImageFormat::Exr: writeExr(tmp.string(), path, image); break;
      case ImageFormat::Pfm: writePfm(tmp.string(), path, image); break;
      case ImageFormat::Png: {
        const auto bytes = toneMapSrgb8(image, exposure);
        if (!stbi_write_png(tmp.c_str(), image.width, image.height, 3, bytes.data(), 3 * image.width))
          throw ImageError(path + ": cannot write PNG");
        break;
      }
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw ImageError(path + ": cannot move the finished image into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw;
  }
}

}  // namespace pathlab
