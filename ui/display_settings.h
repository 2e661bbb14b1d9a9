// Display-only settings (never reset accumulation): exposure and tone mapping of the shown image.
#pragma once

namespace pathlab::ui {

enum class ToneMap { Clamp };

struct DisplaySettings {
  float exposure = 0.f;  // stops
  ToneMap toneMap = ToneMap::Clamp;
  bool operator==(const DisplaySettings&) const = default;
};

// Display value of a linear radiance channel: exposure, clamp, sRGB encode (as PNG output does).
float displayValue(float linear, const DisplaySettings& settings);

}  // namespace pathlab::ui
