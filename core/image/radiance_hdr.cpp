// Radiance RGBE (.hdr) decoding, flat and run-length encoded, bounded by construction: every run
// advances the scanline and every read is checked against the end of the bytes (stb_image 2.27
// loops forever on an empty run at the end of a truncated file, CVE-2021-42715).
#include "core/image/image_budget.h"
#include "core/image/image_read.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace pathlab {
namespace {

[[noreturn]] void hdrFail(const std::string& name, const std::string& what) {
  throw ImageError(name + ": cannot read the HDR image (" + what + ")");
}

class Reader {
 public:
  Reader(const std::vector<unsigned char>& bytes, const std::string& name) : bytes_(bytes), name_(name) {}
  size_t left() const { return bytes_.size() - pos_; }
  unsigned char next() {
    if (pos_ >= bytes_.size()) hdrFail(name_, "truncated HDR data (the file ends inside the pixels)");
    return bytes_[pos_++];
  }
  // One header line without its '\n'; a header line longer than any Radiance writes is refused.
  std::string line() {
    std::string text;
    for (;;) {
      if (pos_ >= bytes_.size()) hdrFail(name_, "truncated HDR header");
      const char c = char(bytes_[pos_++]);
      if (c == '\n') return text;
      if (text.size() > 4096) hdrFail(name_, "not a Radiance HDR file (header line too long)");
      text += c;
    }
  }

 private:
  const std::vector<unsigned char>& bytes_;
  const std::string& name_;
  size_t pos_ = 0;
};

// Greg Ward's RGBE: a shared exponent e, mantissas / 256 (as stb_image, so images keep their values).
void rgbeToFloat(const unsigned char rgbe[4], float* out) {
  if (rgbe[3] == 0) {
    out[0] = out[1] = out[2] = 0.f;
    return;
  }
  const float f = std::ldexp(1.f, int(rgbe[3]) - (128 + 8));
  for (int c = 0; c < 3; ++c) out[c] = float(rgbe[c]) * f;
}

// "-Y H +X W", the only orientation pathlab (and stb_image) reads.
void parseResolution(const std::string& text, const std::string& name, int64_t& width, int64_t& height) {
  long long h = 0, w = 0;
  int end = 0;
  if (std::sscanf(text.c_str(), "-Y %lld +X %lld%n", &h, &w, &end) != 2 || size_t(end) != text.size())
    hdrFail(name, "unsupported HDR resolution line '" + text.substr(0, 40) + "' (only -Y H +X W)");
  width = w;
  height = h;
}

// One new-style RLE scanline's four components (header already read): runs "128+n, value" and
// literals "n, n values" with 1 <= n <= what is left of the scanline.
void readRleScanline(Reader& in, const std::string& name, int width, std::vector<unsigned char>& scanline) {
  for (int k = 0; k < 4; ++k) {
    int i = 0;
    while (i < width) {
      int count = in.next();
      const bool run = count > 128;
      if (run) count -= 128;
      if (count == 0 || count > width - i)
        hdrFail(name, "corrupt HDR run length " + std::to_string(count) + " at texel " +
                         std::to_string(i) + " of a scanline of " + std::to_string(width));
      if (run) {
        const unsigned char value = in.next();
        for (int z = 0; z < count; ++z) scanline[4 * size_t(i++) + size_t(k)] = value;
      } else {
        for (int z = 0; z < count; ++z) scanline[4 * size_t(i++) + size_t(k)] = in.next();
      }
    }
  }
}

}  // namespace

Image decodeRadianceHdr(const std::vector<unsigned char>& bytes, const std::string& name) {
  Reader in(bytes, name);
  const std::string magic = in.line();
  if (magic != "#?RADIANCE" && magic != "#?RGBE") hdrFail(name, "not a Radiance HDR file (bad magic)");
  bool rgbe = false;
  for (std::string l = in.line(); !l.empty(); l = in.line())
    if (l == "FORMAT=32-bit_rle_rgbe") rgbe = true;
    else if (l.rfind("FORMAT=", 0) == 0) hdrFail(name, "unsupported HDR " + l.substr(0, 40));
  if (!rgbe) hdrFail(name, "HDR header has no FORMAT=32-bit_rle_rgbe");
  int64_t width = 0, height = 0;
  parseResolution(in.line(), name, width, height);
  // RLE only for 8 <= width < 32768 (Radiance's rule); a flat texel takes 4 bytes, an RLE scanline
  // at least 4 + 4 x 2 bytes per 127 texels (runs of 127).
  const bool mayBeRle = width >= 8 && width < 32768;
  const uint64_t perLine = mayBeRle ? 4 + 8 * ((uint64_t(width) + 126) / 127) : 4 * uint64_t(std::max<int64_t>(width, 0));
  checkClaimedSize(name, "HDR", width, height, std::max<int64_t>(height, 0) * perLine, in.left());
  Image img{int(width), int(height), std::vector<float>(3 * size_t(width) * size_t(height))};
  std::vector<unsigned char> scanline(4 * size_t(width));
  size_t texel = 0;
  const size_t texels = size_t(width) * size_t(height);
  bool flat = !mayBeRle;
  for (int y = 0; y < img.height && !flat; ++y) {
    unsigned char head[4];
    for (unsigned char& b : head) b = in.next();
    if (head[0] != 2 || head[1] != 2 || (head[2] & 0x80)) {
      if (y > 0) hdrFail(name, "corrupt HDR scanline " + std::to_string(y) + " (not run-length encoded)");
      rgbeToFloat(head, img.rgb.data());  // a flat file: these bytes were its first texel
      texel = 1;
      flat = true;
      break;
    }
    if ((int(head[2]) << 8 | int(head[3])) != width)
      hdrFail(name, "corrupt HDR scanline " + std::to_string(y) + " (length differs from the width)");
    readRleScanline(in, name, int(width), scanline);
    for (int x = 0; x < width; ++x) rgbeToFloat(&scanline[4 * size_t(x)], &img.rgb[3 * texel++]);
  }
  if (flat) {
    if (in.left() < 4 * (texels - texel)) hdrFail(name, "truncated HDR data (the file ends inside the pixels)");
    for (; texel < texels; ++texel) {
      unsigned char rgbe[4];
      for (unsigned char& b : rgbe) b = in.next();
      rgbeToFloat(rgbe, &img.rgb[3 * texel]);
    }
  }
  return img;
}

}  // namespace pathlab
