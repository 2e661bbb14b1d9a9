// The size an image file may claim: checked against a memory budget and against what the file's
// bytes can hold before a decoder allocates, so a lying header costs nothing.
#pragma once

#include <cstdint>
#include <string>

namespace pathlab {

// 2^27 texels (16384 x 8192): 1.5 GiB as RGB floats, 2 GiB in tinyexr's RGBA buffer.
constexpr uint64_t kMaxImageTexels = uint64_t(1) << 27;

// Throws ImageError "NAME: the FORMAT header claims WxH ..." when width or height is not
// positive, the texels exceed kMaxImageTexels, or the file's `available` bytes are fewer than the
// `needed` bytes such an image takes at the least (the file is truncated or the header lies).
void checkClaimedSize(const std::string& name, const char* format, int64_t width, int64_t height, uint64_t needed,
                      uint64_t available);

}  // namespace pathlab
