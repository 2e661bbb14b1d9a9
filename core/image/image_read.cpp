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

// tinyexr's LoadEXRFromMemory leaks its header and image on every error path (found by
// tests/fuzz/image_decoder_fuzz.cpp), so its steps are taken here with the frees on all paths.
class ExrDecoding {
 public:
  explicit ExrDecoding(const std::string& name) : name_(name) {
    InitEXRHeader(&header_);
    InitEXRImage(&image_);
  }
  ~ExrDecoding() {
    if (imageLoaded_) FreeEXRImage(&image_);
    if (headerParsed_) FreeEXRHeader(&header_);
  }
  ExrDecoding(const ExrDecoding&) = delete;
  ExrDecoding& operator=(const ExrDecoding&) = delete;

  Image decode(const std::vector<unsigned char>& bytes) {
    EXRVersion version;
    if (ParseEXRVersionFromMemory(&version, bytes.data(), bytes.size()) != TINYEXR_SUCCESS)
      fail("not an OpenEXR file");
    if (version.multipart || version.non_image) fail("multi-part or deep files are not supported");
    if (version.tiled) fail("tiled files are not supported (write it as scanlines)");
    checkAttributes(bytes);
    headerParsed_ = true;  // a failed parse may have allocated channels and attributes: freed all the same
    if (ParseEXRHeaderFromMemory(&header_, &version, bytes.data(), bytes.size(), &err_) != TINYEXR_SUCCESS)
      fail("bad header");
    const int64_t w = int64_t(header_.data_window.max_x) - header_.data_window.min_x + 1;
    const int64_t h = int64_t(header_.data_window.max_y) - header_.data_window.min_y + 1;
    const uint64_t channels = uint64_t(std::max(header_.num_channels, 1));
    const bool compressed = header_.compression_type != TINYEXR_COMPRESSIONTYPE_NONE;
    // At least two bytes (half floats) per channel and texel, losslessly compressed at most kMaxCompressionRatio.
    const uint64_t texels = w > 0 && h > 0 && uint64_t(w) <= kMaxImageTexels / uint64_t(h) ? uint64_t(w * h) : 0;
    checkClaimedSize(name_, "EXR", w, h, (2 * channels * texels) / (compressed ? kMaxCompressionRatio : 1), bytes.size());
    int rgb[3] = {-1, -1, -1};
    for (int c = 0; c < header_.num_channels; ++c) {
      const std::string channel = header_.channels[c].name;
      if (channel == "R" || channel == "Y" || header_.num_channels == 1) rgb[0] = rgb[0] < 0 ? c : rgb[0];
      if (channel == "G") rgb[1] = c;
      if (channel == "B") rgb[2] = c;
      if (header_.pixel_types[c] == TINYEXR_PIXELTYPE_HALF) header_.requested_pixel_types[c] = TINYEXR_PIXELTYPE_FLOAT;
      if (header_.pixel_types[c] == TINYEXR_PIXELTYPE_UINT) fail("channel " + channel + " is not half or float");
    }
    if (rgb[0] < 0) fail("no R, G, B (or single) channel");
    if (rgb[1] < 0 || rgb[2] < 0) rgb[1] = rgb[2] = rgb[0];  // grey: one channel for all three
    imageLoaded_ = true;
    if (LoadEXRImageFromMemory(&image_, &header_, bytes.data(), bytes.size(), &err_) != TINYEXR_SUCCESS) {
      imageLoaded_ = false;  // tinyexr frees what it allocated before failing
      fail("bad pixel data");
    }
    Image img{image_.width, image_.height, std::vector<float>(3 * size_t(image_.width) * size_t(image_.height))};
    // Scanlines only (tiled files are refused above): one plane a channel, row-major.
    for (size_t i = 0; i < size_t(img.width) * size_t(img.height); ++i)
      for (size_t c = 0; c < 3; ++c) img.rgb[3 * i + c] = reinterpret_cast<const float*>(image_.images[rgb[c]])[i];
    return img;
  }

 private:
  // Debian's tinyexr asserts (aborts) on a "type" attribute that does not match the layout and on a
  // "tiles" attribute of the wrong size (found by the fuzzer): the header's attributes (name, type
  // name, 32-bit size, value; an empty name ends them) are walked here first. A malformed walk
  // stops and is left to tinyexr's own checks.
  void checkAttributes(const std::vector<unsigned char>& bytes) {
    size_t pos = 8;  // magic and version
    auto cstring = [&](std::string& out) {
      const auto end = std::find(bytes.begin() + std::ptrdiff_t(pos), bytes.end(), 0);
      if (end == bytes.end()) return false;
      out.assign(bytes.begin() + std::ptrdiff_t(pos), end);
      pos = size_t(end - bytes.begin()) + 1;
      return true;
    };
    std::string name, type;
    while (pos < bytes.size() && bytes[pos] != 0) {
      if (!cstring(name) || !cstring(type) || bytes.size() - pos < 4) return;
      const uint32_t size = uint32_t(bytes[pos]) | uint32_t(bytes[pos + 1]) << 8 | uint32_t(bytes[pos + 2]) << 16 |
                            uint32_t(bytes[pos + 3]) << 24;
      pos += 4;
      if (bytes.size() - pos < size) return;
      if (name == "tiles") fail("tiled files are not supported (write it as scanlines)");
      if (name == "type" && size > 0 && bytes[pos] != 0) {
        const std::string value(bytes.begin() + std::ptrdiff_t(pos),
                                std::find(bytes.begin() + std::ptrdiff_t(pos), bytes.begin() + std::ptrdiff_t(pos + size), 0));
        if (value != "scanlineimage") fail("only scanline images are supported, not type '" + value.substr(0, 40) + "'");
      }
      pos += size;
    }
  }

  [[noreturn]] void fail(const std::string& what) {
    std::string msg = err_ ? err_ : what;
    if (err_) FreeEXRErrorMessage(err_);
    err_ = nullptr;
    // tinyexr's messages end in a newline and may hold several lines: one line, as every refusal.
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    while (!msg.empty() && msg.back() == ' ') msg.pop_back();
    throw ImageError(name_ + ": cannot read EXR: " + msg);
  }

  const std::string& name_;
  EXRHeader header_;
  EXRImage image_;
  const char* err_ = nullptr;
  bool headerParsed_ = false, imageLoaded_ = false;
};

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
    case ImageFormat::Exr: return ExrDecoding(name).decode(bytes);
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
