// The convergence panel's logic without ImGui: the error view's colour map and scale (the CPU
// mirror of the shader). The technique table's rows are tested with the core
// (tests/metrics/technique_table_test.cpp).
#include "ui/display/display_settings.h"
#include "ui/input/input_script.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace pathlab::ui {
namespace {

TEST(ErrorView, ViridisEndsAndMonotoneLightness) {
  // matplotlib's viridis: (0.267, 0.005, 0.329) at 0, (0.993, 0.906, 0.144) at 1.
  const Vec3 lo = viridis(0.f), hi = viridis(1.f), mid = viridis(0.5f);
  EXPECT_NEAR(lo.r, 0.267f, 0.02f);
  EXPECT_NEAR(lo.g, 0.005f, 0.02f);
  EXPECT_NEAR(lo.b, 0.329f, 0.02f);
  EXPECT_NEAR(hi.r, 0.993f, 0.02f);
  EXPECT_NEAR(hi.g, 0.906f, 0.02f);
  EXPECT_NEAR(hi.b, 0.144f, 0.02f);
  EXPECT_NEAR(mid.r, 0.128f, 0.02f);  // (0.128, 0.567, 0.551)
  EXPECT_NEAR(mid.g, 0.567f, 0.02f);
  float previous = -1.f;
  for (float t = 0.f; t <= 1.f; t += 0.05f) {
    const float luma = luminance(viridis(t));
    EXPECT_GT(luma, previous) << t;
    previous = luma;
  }
}

TEST(ErrorView, ScaleAndColourOfAPixel) {
  DisplaySettings d;
  d.errorLogMin = -4.f;
  d.errorLogMax = 0.f;
  EXPECT_FLOAT_EQ(errorBarPosition(1e-2f, d), 0.5f);
  EXPECT_FLOAT_EQ(errorBarPosition(0.f, d), 0.f);
  EXPECT_FLOAT_EQ(errorBarPosition(1e3f, d), 1.f);
  d.errorLog = false;
  d.errorLinearMax = 0.5f;
  EXPECT_FLOAT_EQ(errorBarPosition(0.25f, d), 0.5f);
  // A pixel of (2, 1, 1) over a reference of 1: relative squared error (1/1.01)/3.
  d.errorLog = true;
  const float e = (1.f / 1.01f) / 3.f;
  const Vec3 c = errorColour(Spectrum(2.f, 1.f, 1.f), Spectrum(1.f), d);
  const Vec3 expected = viridis((std::log10(e) + 4.f) / 4.f);
  EXPECT_NEAR(c.r, expected.r, 1e-5f);
  EXPECT_NEAR(c.g, expected.g, 1e-5f);
  // No error: the bottom of the scale.
  const Vec3 z = errorColour(Spectrum(1.f), Spectrum(1.f), d);
  EXPECT_NEAR(z.g, viridis(0.f).g, 1e-6f);
  // Absolute error: exposure plays no part.
  d.errorKind = PixelError::Absolute;
  d.exposure = 5.f;
  EXPECT_NEAR(errorColour(Spectrum(1.5f), Spectrum(1.f), d).g, viridis((std::log10(0.5f) + 4.f) / 4.f).g, 1e-5f);
}

// Scripts that compare configurations wait for a sample count instead of counting frames.
TEST(InputScript, WaitForSamples) {
  const std::vector<InputEvent> events = parseInputScript("20:wait=8;21:key=U");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(inputAt(events, 20).waitSpp, std::optional<uint64_t>(8));
  EXPECT_FALSE(inputAt(events, 21).waitSpp.has_value());
  EXPECT_FALSE(inputAt(events, 19).waitSpp.has_value());
  EXPECT_THROW(parseInputScript("3:wait=0"), std::invalid_argument);
  EXPECT_THROW(parseInputScript("3:wait=x"), std::invalid_argument);
  // The reference shortcuts are scriptable.
  EXPECT_NO_THROW(parseInputScript("1:key=Ctrl+R;2:key=X;3:key=P"));
}

}  // namespace
}  // namespace pathlab::ui
