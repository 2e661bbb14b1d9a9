// The image size a camera's aspect ratio asks for (see image_size.h).
#include "core/camera/image_size.h"

#include <algorithm>
#include <cmath>

namespace pathlab {

namespace {

int roundSide(double side) { return static_cast<int>(std::max(1.0, std::round(side))); }

}  // namespace

std::optional<float> cameraAspect(const std::optional<CameraDesc>& override, const CameraDesc& scene) {
  return override && override->aspectRatio ? override->aspectRatio : scene.aspectRatio;
}

Vec2i imageSizeForAspect(std::optional<float> aspect, std::optional<int> width, std::optional<int> height,
                         int longestSide) {
  const double a = aspect && *aspect > 0.f && std::isfinite(*aspect) ? static_cast<double>(*aspect) : 1.0;
  if (width && height) return {*width, *height};
  if (width) return {*width, roundSide(*width / a)};
  if (height) return {roundSide(*height * a), *height};
  return a >= 1.0 ? Vec2i(longestSide, roundSide(longestSide / a)) : Vec2i(roundSide(longestSide * a), longestSide);
}

}  // namespace pathlab
