// Display transform of the viewer: the same exposure and sRGB encoding as PNG output.
#include "ui/display_settings.h"

#include "core/film/image_io.h"

namespace pathlab::ui {

float displayValue(float linear, const DisplaySettings& settings) { return exposeToSrgb(linear, settings.exposure); }

}  // namespace pathlab::ui
