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

// The default first merge radius keeps a disk's expected count of light vertices, pi r^2 x
// pixels x their density per subpath, the same at every image size: r^2 x pixels is constant,
// with SmallVCM's 0.003 at its 512 x 512. An explicit radius is kept as given.
TEST(MergeRadius, TheDefaultKeepsTheLightVerticesPerDiskAtEveryImageSize) {
  RenderSettings s;
  s.width = s.height = 512;
  EXPECT_FLOAT_EQ(firstMergeRadius(s), kDefaultMergeRadius);
  const double perDisk = double(kDefaultMergeRadius) * kDefaultMergeRadius * 512.0 * 512.0;
  for (const auto& [w, h] : {std::pair{256, 256}, {1024, 256}, {640, 480}, {1920, 1080}, {37, 5}}) {
    s.width = w, s.height = h;
    const double r = firstMergeRadius(s);
    EXPECT_NEAR(r * r * w * h / perDisk, 1.0, 1e-5) << w << " x " << h;
  }
  s.width = s.height = 256;
  EXPECT_FLOAT_EQ(firstMergeRadius(s), 2.f * kDefaultMergeRadius);
  s.width = s.height = 1;  // a single pixel would want 1.5: held at the most --radius takes
  EXPECT_FLOAT_EQ(firstMergeRadius(s), kMaxMergeRadius);
  s.mergeRadius = 0.01f;
  EXPECT_FLOAT_EQ(firstMergeRadius(s), 0.01f);
}

}  // namespace
}  // namespace pathlab
