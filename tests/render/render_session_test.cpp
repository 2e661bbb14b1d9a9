// Progressive rendering: replayable samples, results independent of the thread count, and the
// film's guard counted.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <optional>

namespace pathlab {
namespace {

RenderSettings sessionSettings() {
  RenderSettings s;
  s.width = 24;
  s.height = 16;
  s.seed = 5;
  return s;
}

TEST(RenderSession, SameSeedSameImageWhateverTheThreadCount) {
  Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  auto render = [&](size_t threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
    RenderSession session(scene, sessionSettings());
    for (int i = 0; i < 3; ++i) session.renderPass();
    EXPECT_EQ(session.counters().cameraSamples, 3u * 24u * 16u);
    EXPECT_EQ(session.counters().discarded(), 0u);
    return session.image();
  };
  const Image one = render(1), two = render(2);
  EXPECT_EQ(one.rgb, two.rgb);
  RenderSettings other = sessionSettings();
  other.seed = 6;
  RenderSession different(scene, other);
  different.renderPass();
  different.renderPass();
  different.renderPass();
  EXPECT_NE(different.image().rgb, one.rgb);
}

// Without --radius a merge pass uses firstMergeRadius: at 24 x 16 pixels 0.003 x sqrt(512^2 / 384).
TEST(RenderSession, MergesUseTheDefaultRadiusOfTheImageSize) {
  Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  auto render = [&](std::optional<float> radius) {
    RenderSettings s = sessionSettings();
    s.integrator = IntegratorKind::Bpt;
    s.techniques = TechniqueSet::parse("all;m=all");
    s.mergeRadius = radius;
    s.mergeNonCaustic = 1.f;  // every light vertex: 384 of them a pass
    RenderSession session(scene, s);
    for (int i = 0; i < 2; ++i) session.renderPass();
    return session.image();
  };
  const Image unset = render(std::nullopt);
  EXPECT_EQ(unset.rgb, render(static_cast<float>(double{0.003f} * std::sqrt(512.0 * 512.0 / (24.0 * 16.0)))).rgb);
  EXPECT_NE(unset.rgb, render(0.003f).rgb);  // the radius reaches the image
}

// Any sample can be replayed alone: the sum over passes of replaySample is the film's pixel.
TEST(RenderSession, ReplayReproducesThePixel) {
  Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  RenderSession session(scene, sessionSettings());
  for (int i = 0; i < 4; ++i) session.renderPass();
  Counters c;
  for (const auto& [x, y] : {std::pair{3, 4}, std::pair{12, 8}, std::pair{23, 15}}) {
    DVec3 sum(0.0);
    for (uint64_t pass = 0; pass < 4; ++pass) sum += DVec3(session.replaySample(x, y, pass, c));
    const Vec3 pixel = session.image().at(x, y);
    for (int ch = 0; ch < 3; ++ch) EXPECT_FLOAT_EQ(pixel[ch], static_cast<float>(sum[ch] / 4.0));
  }
}

}  // namespace
}  // namespace pathlab
