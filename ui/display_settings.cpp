// Display transform shared by the viewer and PNG output.
#include "ui/display_settings.h"

#include "core/scene/texture.h"

#include <algorithm>
#include <cmath>

namespace pathlab::ui {

float displayValue(float linear, const DisplaySettings& settings) {
  const float v = linear * std::exp2(settings.exposure);
  return linearToSrgb(std::isfinite(v) ? std::clamp(v, 0.f, 1.f) : 0.f);
}

}  // namespace pathlab::ui
