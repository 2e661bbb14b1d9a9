// Display-only settings (never reset accumulation): exposure, tone map and false colour of the
// shown image, the false-colour error view against a reference, and their CPU reference, which
// shaders/display.frag mirrors.
#pragma once

#include "core/film/film.h"
#include "core/maps/map_colours.h"  // viridis
#include "core/math/types.h"
#include "core/metrics/error_image.h"

#include <cstdint>
#include <vector>

namespace pathlab::ui {

// Clamp: what PNG output does. Filmic: the ACES fit (Narkowicz 2015), which rolls highlights off
// instead of clipping them.
enum class ToneMap { Clamp, Filmic };

struct DisplaySettings {
  float exposure = 0.f;  // stops
  ToneMap toneMap = ToneMap::Clamp;
  bool falseColour = false;  // log10 luminance through the turbo colour map
  float logMin = -3.f;       // false colour range, decades of exposed luminance
  float logMax = 1.f;
  // The error view: per-pixel error against the reference (core/metrics/error_image.h) through
  // the viridis colour map, over [errorLogMin, errorLogMax] decades (log) or [0, errorLinearMax].
  // Exposure does not apply: the error is of the radiance. Shown only while a reference is valid.
  bool errorView = false;
  PixelError errorKind = PixelError::RelativeSquared;
  bool errorLog = true;
  float errorLogMin = -4.f, errorLogMax = 0.f;
  float errorLinearMax = 0.25f;
  bool operator==(const DisplaySettings&) const = default;
};

// Display value of a linear radiance channel: exposure, clamp, sRGB encode (as PNG output does).
float displayValue(float linear, const DisplaySettings& settings);
// The displayed sRGB colour in [0,1] of a linear radiance, exactly as shaders/display.frag.
Vec3 displayColour(const Spectrum& radiance, const DisplaySettings& settings);

Vec3 acesFilmic(const Vec3& x);
Vec3 turbo(float t);  // t clamped to [0,1]

// Position in [0,1] on the error colour bar of a per-pixel error value (0 below the range).
float errorBarPosition(float error, const DisplaySettings& settings);
// The colour the error view shows for a pixel of `image` over `reference`, as the shader does.
Vec3 errorColour(const Spectrum& image, const Spectrum& reference, const DisplaySettings& settings);

// Exposure in stops that brings the mean luminance of `image` to middle grey (0.18); 0 for a
// black image. The technique pyramid's thumbnails each get their own.
float autoExposure(const Image& image);

// RGBA8 of the displayed image, top row first (thumbnails are tone mapped on the CPU).
std::vector<uint8_t> toRgba8(const Image& image, const DisplaySettings& settings);

}  // namespace pathlab::ui
