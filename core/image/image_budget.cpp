// The claimed-size check shared by the image decoders (image_budget.h).
#include "core/image/image_budget.h"

#include "core/image/image_read.h"

namespace pathlab {

void checkClaimedSize(const std::string& name, const char* format, int64_t width, int64_t height, uint64_t needed,
                      uint64_t available) {
  const std::string claim = name + ": the " + format + " header claims " + std::to_string(width) + "x" +
                            std::to_string(height) + " texels";
  if (width <= 0 || height <= 0) throw ImageError(claim + ", an empty image");
  if (uint64_t(width) > kMaxImageTexels / uint64_t(height))
    throw ImageError(claim + ", more than the " + std::to_string(kMaxImageTexels) + " pathlab reads");
  if (needed > available)
    throw ImageError(claim + ", which take at least " + std::to_string(needed) + " bytes, but the file has " +
                     std::to_string(available) + " (truncated)");
}

}  // namespace pathlab
