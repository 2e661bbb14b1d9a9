// Where the image goes in the room the panels leave: the largest rectangle of the camera's aspect,
// centred (letterboxed or pillarboxed), so the scene is never cropped whatever the window's shape.
#pragma once

#include "core/math/types.h"

#include <optional>

namespace pathlab::ui {

// Framebuffer pixels, origin top-left (as ImGui's).
struct PixelRect {
  Vec2i origin{0}, size{0};
  bool contains(Vec2 p) const {
    return p.x >= static_cast<float>(origin.x) && p.y >= static_cast<float>(origin.y) &&
           p.x < static_cast<float>(origin.x + size.x) && p.y < static_cast<float>(origin.y + size.y);
  }
  bool operator==(const PixelRect&) const = default;
};

// The largest rectangle of `aspect` (width / height) inside `room`, centred; the bars left over
// are split evenly (the odd pixel goes after). No aspect (a glTF camera without aspectRatio, which
// means "the viewport's"): the whole room. An empty room stays empty.
PixelRect fitAspect(const PixelRect& room, std::optional<float> aspect);

}  // namespace pathlab::ui
