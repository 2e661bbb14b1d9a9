// Image files read through the guarded reader and decoded from memory: tinyexr after a header check,
// a hand-written PFM reader (image_read.h); Radiance HDR is in radiance_hdr.cpp.
#include "core/image/image_read.h"

#include "core/image/image_budget.h"
#include "core/io/guarded_file.h"

#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

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

// Decoded bytes per byte of a compressed file at the most: deflate's limit is 1032:1 (EXR's ZIP and
// PIZ modes; RLE reaches 64:1), so a header claiming more than this is refused before decoding.
constexpr uint64_t kMaxCompressionRatio = 1100;

Image decodeExr(const std::vector<unsigned char>& bytes, const std::string& name) {
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
    throw ImageError(name + ": cannot read EXR: not an OpenEXR file");
  if (version.multipart || version.non_image) throw ImageError(name + ": cannot read EXR: multi-part or deep files are not supported");
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  auto fail = [&](const std::string& what) {
    std::string msg = err ? err : what;
    if (err) FreeEXRErrorMessage(err);
    // tinyexr's messages end in a newline and may hold several lines: one line, as every refusal.
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    while (!msg.empty() && msg.back() == ' ') msg.pop_back();
    throw ImageError(name + ": cannot read EXR: " + msg);
  };
  if (ParseEXRHeaderFromMemory(&header, &version, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS)
    fail("bad header");
  const int64_t w = int64_t(header.data_window.max_x) - header.data_window.min_x + 1;
  const int64_t h = int64_t(header.data_window.max_y) - header.data_window.min_y + 1;
  const uint64_t channels = uint64_t(std::max(header.num_channels, 1));
  const bool compressed = header.compression_type != TINYEXR_COMPRESSIONTYPE_NONE;
  FreeEXRHeader(&header);
  // At least two bytes (half floats) per channel and texel, losslessly compressed at most kMaxCompressionRatio.
  const uint64_t texels = w > 0 && h > 0 && uint64_t(w) <= kMaxImageTexels / uint64_t(h) ? uint64_t(w * h) : 0;
  checkClaimedSize(name, "EXR", w, h, (2 * channels * texels) / (compressed ? kMaxCompressionRatio : 1), bytes.size());
  float* rgba = nullptr;
  int width = 0, height = 0;
  if (LoadEXRFromMemory(&rgba, &width, &height, bytes.data(), bytes.size(), &err) != TINYEXR_SUCCESS) fail("unknown error");
  Image img{width, height, std::vector<float>(3 * static_cast<size_t>(width) * static_cast<size_t>(height))};
  for (size_t i = 0; i < static_cast<size_t>(width) * static_cast<size_t>(height); ++i)
    for (size_t c = 0; c < 3; ++c) img.rgb[3 * i + c] = rgba[4 * i + c];
  free(rgba);
  return img;
}

// "PF", width, height and scale as text, one whitespace byte, then little-endian rows bottom-up.
Image decodePfm(const std::vector<unsigned char>& bytes, const std::string& name) {
  size_t pos = 0;
  auto token = [&]() {
    while (pos < bytes.size() && std::isspace(bytes[pos])) ++pos;
    std::string t;
    while (pos < bytes.size() && !std::isspace(bytes[pos]) && t.size() < 64) t += char(bytes[pos++]);
    return t;
  };
  const std::string magic = token(), ws = token(), hs = token(), ss = token();
  if (magic != "PF") throw ImageError(name + ": not a colour PFM file");
  char* end = nullptr;
  const long long w = std::strtoll(ws.c_str(), &end, 10);
  const bool wOk = !ws.empty() && *end == '\0';
  const long long h = std::strtoll(hs.c_str(), &end, 10);
  const bool hOk = !hs.empty() && *end == '\0';
  const float scale = std::strtof(ss.c_str(), &end);
  if (!wOk || !hOk || ss.empty() || *end != '\0' || pos >= bytes.size() || !std::isfinite(scale) || scale == 0.f)
    throw ImageError(name + ": not a colour PFM file (bad header)");
  if (scale > 0.f) throw ImageError(name + ": big-endian PFM is not supported");
  ++pos;  // the single whitespace byte after the scale
  const uint64_t texels = w > 0 && h > 0 && uint64_t(w) <= kMaxImageTexels / uint64_t(h) ? uint64_t(w * h) : 0;
  checkClaimedSize(name, "PFM", w, h, 12 * texels, bytes.size() - pos);
  Image img{int(w), int(h), std::vector<float>(3 * size_t(texels))};
  const size_t row = 3 * size_t(w);
  for (int y = img.height - 1, r = 0; y >= 0; --y, ++r)  // PFM stores rows bottom-up
    std::memcpy(&img.rgb[row * size_t(y)], bytes.data() + pos + sizeof(float) * row * size_t(r), sizeof(float) * row);
  return img;
}

std::vector<unsigned char> readBytes(const std::string& path) {
  try {
    return readGuardedFile(path);
  } catch (const FileError& e) {
    throw ImageError(e.what());
  }
}

}  // namespace

Image decodeImage(const std::vector<unsigned char>& bytes, ImageFormat format, const std::string& name) {
  switch (format) {
    case ImageFormat::Exr: return decodeExr(bytes, name);
    case ImageFormat::Pfm: return decodePfm(bytes, name);
    case ImageFormat::Png: break;
  }
  throw ImageError(name + ": reading PNG is not supported (use .exr or .pfm)");
}

Image readImage(const std::string& path) {
  if (!fs::exists(path)) throw ImageError(path + ": no such file");
  const ImageFormat format = imageFormatOf(path);
  if (format == ImageFormat::Png) return decodeImage({}, format, path);
  return decodeImage(readBytes(path), format, path);
}

Image readRadianceHdr(const std::string& path) { return decodeRadianceHdr(readBytes(path), path); }

}  // namespace pathlab
