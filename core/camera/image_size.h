// The image size a camera's aspect ratio asks for, when the user gives one side or none.
#pragma once

#include "core/camera/camera_desc.h"
#include "core/math/types.h"

#include <optional>

namespace pathlab {

// The longest side of an image whose size nobody gave (`pathlab render` without --width/--height).
constexpr int kDefaultLongestSide = 512;

// An image of aspect `aspect` (width / height; none: square, the glTF "use the viewport's" with
// no viewport to use). Both sides given: exactly those (the user's wish wins over the camera's).
// One given: the other follows the aspect. None: the longest side is `longestSide`. A derived
// side is rounded to the nearest integer (512 / 1.5 = 341.3 -> 341) and is at least 1.
// The aspect the image takes: the override camera's (the viewer's orbit/fly keeps the scene's),
// else the scene camera's: a camera with none of its own (a preset's look-at) shows the same scene.
// None: the scene's camera has no aspectRatio either.
std::optional<float> cameraAspect(const std::optional<CameraDesc>& override, const CameraDesc& scene);

Vec2i imageSizeForAspect(std::optional<float> aspect, std::optional<int> width, std::optional<int> height,
                         int longestSide = kDefaultLongestSide);

}  // namespace pathlab
