// libFuzzer target for the image decoders (issue 37): any byte string, decoded as OpenEXR, PFM and
// Radiance HDR from memory, must decode or throw ImageError with one line naming the input; never
// crash, hang, leak or allocate past kMaxImageTexels (run under ASan + UBSan, see run_fuzz.sh).
#include "core/image/image_read.h"

#include <cstdint>
#include <string>
#include <vector>

namespace {

template <typename Decode>
void decodeOrRefuse(const std::vector<unsigned char>& bytes, const std::string& name, Decode decode) {
  try {
    const pathlab::Image img = decode(bytes, name);
    if (img.rgb.size() != 3 * size_t(img.width) * size_t(img.height)) __builtin_trap();
  } catch (const pathlab::ImageError& e) {
    const std::string what = e.what();
    if (what.find('\n') != std::string::npos || what.rfind(name + ": ", 0) != 0) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<unsigned char> bytes(data, data + size);
  using pathlab::ImageFormat;
  decodeOrRefuse(bytes, "fuzz.exr", [](const auto& b, const auto& n) { return pathlab::decodeImage(b, ImageFormat::Exr, n); });
  decodeOrRefuse(bytes, "fuzz.pfm", [](const auto& b, const auto& n) { return pathlab::decodeImage(b, ImageFormat::Pfm, n); });
  decodeOrRefuse(bytes, "fuzz.hdr", [](const auto& b, const auto& n) { return pathlab::decodeRadianceHdr(b, n); });
  return 0;
}
