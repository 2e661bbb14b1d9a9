// validateSettings refuses a float setting that is not finite or out of range, whatever route it
// came by (CLI, converge configurations, viewer presets and camera), naming the setting and value.
#include "core/render/render_settings.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

namespace pathlab {
namespace {

std::string refusal(const RenderSettings& s) {
  try {
    validateSettings(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(RenderSettingsValidation, NonFiniteFloatSettingsAreRefused) {
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const std::pair<const char*, std::function<void(RenderSettings&, float)>> settings[] = {
      {"MIS beta", [](RenderSettings& s, float v) { s.mis.beta = v; }},
      {"minimum connection", [](RenderSettings& s, float v) { s.mis.minConnection = v; }},
      {"lens aperture", [](RenderSettings& s, float v) { s.lens.apertureRadius = v; }},
      {"focus distance", [](RenderSettings& s, float v) { s.lens.focusDistance = v; }},
      {"camera transform", [](RenderSettings& s, float v) { s.camera = CameraDesc{}; s.camera->cameraToWorld[3][0] = v; }},
      {"camera field of view", [](RenderSettings& s, float v) { s.camera = CameraDesc{}; s.camera->yfov = v; }},
      {"camera aspect ratio", [](RenderSettings& s, float v) { s.camera = CameraDesc{}; s.camera->aspectRatio = v; }},
  };
  ASSERT_EQ(refusal(RenderSettings{}), "");
  for (const auto& [name, set] : settings)
    for (float v : {nan, inf, -inf}) {
      RenderSettings s;
      set(s, v);
      const std::string message = refusal(s);
      EXPECT_NE(message.find(name), std::string::npos) << name << " = " << v << ": '" << message << "'";
      EXPECT_TRUE(message.find("nan") != std::string::npos || message.find("inf") != std::string::npos) << message;
    }
}

TEST(RenderSettingsValidation, OutOfRangeFloatSettingsAreRefused) {
  RenderSettings s;
  s.mis.beta = 1000.f;
  EXPECT_NE(refusal(s).find("MIS beta 1000"), std::string::npos);
  s = {};
  s.lens.apertureRadius = -1.f;
  EXPECT_NE(refusal(s).find("lens aperture -1"), std::string::npos);
  s = {};
  s.lens.focusDistance = 0.f;
  EXPECT_NE(refusal(s).find("focus distance 0"), std::string::npos);
  s = {};
  s.mis.minConnection = 0.f;  // the exclusion turned off
  s.lens = {0.5f, 3.f};
  s.camera = CameraDesc{};
  EXPECT_EQ(refusal(s), "");
}

}  // namespace
}  // namespace pathlab
