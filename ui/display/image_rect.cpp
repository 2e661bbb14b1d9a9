// Fitting the image into the room the panels leave (see image_rect.h).
#include "ui/display/image_rect.h"

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

PixelRect fitAspect(const PixelRect& room, std::optional<float> aspect) {
  if (!aspect || !(*aspect > 0.f) || !std::isfinite(*aspect) || room.size.x <= 0 || room.size.y <= 0) return room;
  const double a = *aspect, w = room.size.x, h = room.size.y;
  // Rounded to the nearest pixel, so the fitted aspect is the camera's within one pixel.
  Vec2i size = w > a * h ? Vec2i(static_cast<int>(std::lround(a * h)), room.size.y)
                         : Vec2i(room.size.x, static_cast<int>(std::lround(w / a)));
  size = glm::clamp(size, Vec2i(1), room.size);
  return {room.origin + (room.size - size) / 2, size};
}

}  // namespace pathlab::ui
