// The display transform's CPU reference (shaders/display.frag mirrors it): clamp equals PNG
// output, the filmic curve is monotone and bounded, false colour maps decades of luminance.
#include "ui/display/display_settings.h"

#include "core/film/image_io.h"

#include <gtest/gtest.h>

namespace pathlab::ui {
namespace {

TEST(DisplaySettings, ClampIsWhatPngOutputDoes) {
  DisplaySettings d;
  d.exposure = 1.5f;
  for (float v : {0.f, 1e-4f, 0.01f, 0.18f, 0.5f, 1.f, 4.f}) {
    const Vec3 c = displayColour(Spectrum(v, 2.f * v, 0.5f * v), d);
    EXPECT_NEAR(c.r, exposeToSrgb(v, d.exposure), 1e-5f) << v;
    EXPECT_NEAR(c.g, exposeToSrgb(2.f * v, d.exposure), 1e-5f) << v;
    EXPECT_NEAR(c.b, exposeToSrgb(0.5f * v, d.exposure), 1e-5f) << v;
    EXPECT_NEAR(displayValue(v, d), exposeToSrgb(v, d.exposure), 1e-6f);
  }
}

TEST(DisplaySettings, FilmicIsMonotoneBoundedAndRollsOffHighlights) {
  float previous = -1.f;
  for (float x = 0.f; x < 100.f; x = x * 1.3f + 0.001f) {
    const float y = acesFilmic(Vec3(x)).r;
    EXPECT_GE(y, previous) << x;
    EXPECT_LE(y, 1.f);
    previous = y;
  }
  EXPECT_NEAR(acesFilmic(Vec3(0.f)).r, 0.f, 1e-6f);
  DisplaySettings d;
  d.toneMap = ToneMap::Filmic;
  // 2.0 clips under clamp but keeps detail under the filmic curve.
  EXPECT_LT(displayColour(Spectrum(2.f), d).r, 1.f);
  EXPECT_LT(displayColour(Spectrum(1.f), d).r, displayColour(Spectrum(2.f), d).r);
}

TEST(DisplaySettings, FalseColourSpansTheLogRange) {
  DisplaySettings d;
  d.falseColour = true;
  d.logMin = -2.f;
  d.logMax = 2.f;
  EXPECT_EQ(displayColour(Spectrum(0.f), d), Vec3(0.f));     // no contribution stays black
  EXPECT_EQ(displayColour(Spectrum(1e-3f), d), Vec3(0.f));   // below the range
  const Vec3 low = displayColour(Spectrum(0.0101f), d), mid = displayColour(Spectrum(1.f), d),
             high = displayColour(Spectrum(1e3f), d);  // above the range: clamped to the top colour
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(low[c], turbo(0.f)[c], 0.02f);
    EXPECT_NEAR(mid[c], turbo(0.5f)[c], 1e-4f);
    EXPECT_NEAR(high[c], turbo(1.f)[c], 1e-4f);
  }
  // Turbo runs from near black through blue, green and yellow to dark red.
  EXPECT_LT(turbo(0.f).r + turbo(0.f).g + turbo(0.f).b, 0.5f);
  EXPECT_GT(turbo(0.15f).b, turbo(0.15f).r);
  EXPECT_GT(turbo(0.5f).g, 0.8f);
  EXPECT_GT(turbo(1.f).r, turbo(1.f).b);
  // Exposure shifts the range: one decade = log2(10) stops.
  d.exposure = std::log2(10.f);
  const Vec3 shifted = displayColour(Spectrum(0.1f), d);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(shifted[c], mid[c], 1e-3f);
}

TEST(DisplaySettings, AutoExposureBringsTheMeanToMiddleGrey) {
  Image image{2, 1, {0.01f, 0.01f, 0.01f, 0.03f, 0.03f, 0.03f}};
  EXPECT_NEAR(autoExposure(image), std::log2(0.18f / 0.02f), 1e-4f);
  Image black{2, 1, std::vector<float>(6, 0.f)};
  EXPECT_EQ(autoExposure(black), 0.f);
  DisplaySettings d;
  d.exposure = autoExposure(image);
  const std::vector<uint8_t> rgba = toRgba8(image, d);
  ASSERT_EQ(rgba.size(), 8u);
  EXPECT_EQ(rgba[3], 255);
  EXPECT_LT(rgba[0], rgba[4]);
}

}  // namespace
}  // namespace pathlab::ui
