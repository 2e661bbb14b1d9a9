// Generations of the progressive renderer (issue 3): a settings change restarts accumulation and
// the images of a generation are exactly those of a standalone render with its settings, however
// often the settings changed before; previews come first; pause and target stop the worker.
#include "core/render/progressive_renderer.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace pathlab {
namespace {

std::shared_ptr<const Scene> sharedCornellBox() {
  static const auto scene =
      std::make_shared<const Scene>(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  return scene;
}

RenderSettings small(IntegratorKind integrator, uint64_t seed) {
  RenderSettings s;
  s.width = 48;
  s.height = 32;
  s.maxLength = 5;
  s.seed = seed;
  s.integrator = integrator;
  return s;
}

Image standalone(const RenderSettings& settings, uint64_t passes) {
  RenderSession session(*sharedCornellBox(), settings);
  for (uint64_t i = 0; i < passes; ++i) session.renderPass();
  return session.image();
}

// Waits for a full-resolution snapshot of the current generation with exactly `spp` passes
// (the renderer is stopped at that target).
RenderSnapshot settledSnapshot(const ProgressiveRenderer& r, uint64_t spp) {
  EXPECT_TRUE(r.waitForSpp(spp, 60.0));
  RenderSnapshot snap;
  EXPECT_TRUE(r.snapshot(snap));
  return snap;
}

void expectSameImage(const Image& a, const Image& b) {
  ASSERT_EQ(a.width, b.width);
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  // Path tracing is bitwise deterministic; bidirectional splats are atomic double sums whose
  // order depends on the thread schedule, hence the small relative tolerance.
  for (size_t i = 0; i < a.rgb.size(); ++i)
    ASSERT_NEAR(a.rgb[i], b.rgb[i], 1e-5 * std::max(std::abs(a.rgb[i]), std::abs(b.rgb[i])) + 1e-8) << "value " << i;
}

TEST(ProgressiveRenderer, AGenerationIsAStandaloneRender) {
  ProgressiveRenderer renderer(sharedCornellBox(), small(IntegratorKind::Pt, 1), 2);
  renderer.setTargetSpp(3);
  RenderSnapshot first = settledSnapshot(renderer, 3);
  EXPECT_FALSE(first.preview);
  EXPECT_EQ(first.samplesPerPixel, 3u);
  EXPECT_EQ(first.settings, small(IntegratorKind::Pt, 1));
  expectSameImage(first.image, standalone(small(IntegratorKind::Pt, 1), 3));

  // Toggle many times quickly; only the last settings may reach the image.
  for (int i = 0; i < 25; ++i) {
    RenderSettings s = small(i % 2 ? IntegratorKind::Bpt : IntegratorKind::Lt, static_cast<uint64_t>(i));
    s.mis.heuristic = i % 3 ? MisHeuristic::Power : MisHeuristic::Balance;
    EXPECT_TRUE(renderer.setSettings(s));
  }
  RenderSettings last = small(IntegratorKind::Bpt, 99);
  last.techniques = TechniqueSet::parse("s=0;s=1;t=1");
  EXPECT_TRUE(renderer.setSettings(last));
  EXPECT_FALSE(renderer.setSettings(last));  // unchanged: no new generation
  RenderSettings same = last;  // the same techniques spelled another way: no new generation either
  same.techniques = TechniqueSet::parse("t=1; 0,3; s=1; s=0; k=1");
  EXPECT_FALSE(renderer.setSettings(same));
  const RenderSnapshot snap = settledSnapshot(renderer, 3);
  EXPECT_EQ(snap.generation, renderer.generation());
  EXPECT_GT(snap.generation, first.generation);
  EXPECT_EQ(snap.settings, last);
  EXPECT_EQ(snap.counters.discarded(), 0u);
  expectSameImage(snap.image, standalone(last, 3));
}

TEST(ProgressiveRenderer, PreviewsComeFirstAtLowResolution) {
  RenderSettings s = small(IntegratorKind::Bpt, 2);
  s.width = 160;
  s.height = 120;
  ProgressiveRenderer renderer(sharedCornellBox(), s, 2);
  renderer.setTargetSpp(1);
  ASSERT_TRUE(renderer.waitForSpp(1, 60.0));
  RenderSnapshot snap;
  ASSERT_TRUE(renderer.snapshot(snap));
  EXPECT_FALSE(snap.preview);
  EXPECT_EQ(snap.image.width, 160);
  // Three previews (1/8, 1/4, 1/2) and one full pass were published: versions 1..4.
  EXPECT_EQ(snap.version, 4u);
  EXPECT_GT(snap.counters.cameraSamples, 160u * 120u);  // the previews' samples count too
  EXPECT_FALSE(renderer.snapshot(snap));  // nothing newer
}

TEST(ProgressiveRenderer, RefusesBadSettingsAndKeepsTheOldOnes) {
  ProgressiveRenderer renderer(sharedCornellBox(), small(IntegratorKind::Bpt, 3), 1);
  const uint64_t generation = renderer.generation();
  RenderSettings bad = small(IntegratorKind::Bpt, 3);
  bad.techniques = TechniqueSet::parse("7,7");
  EXPECT_THROW(renderer.setSettings(bad), std::invalid_argument);
  EXPECT_EQ(renderer.generation(), generation);
  EXPECT_EQ(renderer.settings(), small(IntegratorKind::Bpt, 3));
}

// The scene's own camera can refuse settings too: light tracing or a lens through an orthographic
// camera (issue 15) is refused by setSettings and setScene, on the caller's thread, never by the
// render thread (where it would end the process).
TEST(ProgressiveRenderer, RefusesWhatAnOrthographicSceneCameraCannotDo) {
  SceneDesc desc = loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/isometric.gltf");
  ASSERT_TRUE(desc.camera && desc.camera->orthographic);
  const auto iso = std::make_shared<const Scene>(std::move(desc));
  RenderSettings s;
  s.width = 16;
  s.height = 12;
  ProgressiveRenderer renderer(iso, s, 1);
  RenderSettings lt = s;
  lt.integrator = IntegratorKind::Lt;
  EXPECT_THROW(renderer.setSettings(lt), std::invalid_argument);
  RenderSettings lens = s;
  lens.lens.apertureRadius = 0.05f;
  EXPECT_THROW(renderer.setSettings(lens), std::invalid_argument);
  EXPECT_EQ(renderer.settings(), s);
  // A scene with a perspective camera takes light tracing; going back to the orthographic one
  // with it is refused.
  ProgressiveRenderer box(sharedCornellBox(), lt, 1);
  EXPECT_THROW(box.setScene(iso, lt), std::invalid_argument);
  EXPECT_THROW(ProgressiveRenderer(iso, lt, 1), std::invalid_argument);
  ASSERT_TRUE(renderer.waitForSpp(1, 30.0));
}

TEST(ProgressiveRenderer, PyramidThumbnailsArePublished) {
  RenderSettings s = small(IntegratorKind::Bpt, 4);
  s.pyramidLength = 2;
  ProgressiveRenderer renderer(sharedCornellBox(), s, 2);
  renderer.setThumbnailSide(16);
  renderer.setTargetSpp(3);
  ASSERT_TRUE(renderer.waitForSpp(1, 60.0));
  std::vector<TechniqueThumbnail> thumbs;
  uint64_t version = 0;
  // The thumbnails follow the image's publication (a new generation first publishes an empty
  // list), and setThumbnailSide applies from the next publication on: wait for filled thumbnails
  // of the new size.
  auto ready = [&] {
    renderer.pyramid(thumbs, version);
    return !thumbs.empty() && thumbs[0].weighted.width == 16;
  };
  for (int i = 0; i < 1000 && !ready(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_EQ(thumbs.size(), 5u);  // (0,2) (1,1) (0,3) (1,2) (2,1)
  EXPECT_EQ(thumbs[3].s, 1);
  EXPECT_EQ(thumbs[3].t, 2);
  EXPECT_EQ(thumbs[3].weighted.width, 16);
  EXPECT_EQ(thumbs[3].unweighted.height, 10);  // 48 x 32 scaled to a longer side of 16 (one rounded down)
}

TEST(ProgressiveRenderer, PausedRendersNothingNew) {
  ProgressiveRenderer renderer(sharedCornellBox(), small(IntegratorKind::Pt, 5), 2);
  ASSERT_TRUE(renderer.waitForSpp(1, 60.0));
  renderer.setPaused(true);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the pass in flight ends
  RenderSnapshot a;
  renderer.snapshot(a);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  RenderSnapshot b = a;
  EXPECT_FALSE(renderer.snapshot(b));
  renderer.setPaused(false);
  EXPECT_TRUE(renderer.waitForSpp(a.samplesPerPixel + 1, 60.0));
}

// The outlier finder in the viewer's renderer (issue 34): the list it publishes after a full pass
// is the one a standalone render keeps over the same passes (the finder starts between passes, at
// list.firstPass); a new generation starts with an empty list; the path tracer publishes none.
OutlierList settledOutliers(const ProgressiveRenderer& r, uint64_t passes) {
  OutlierList list;
  uint64_t version = 0;
  const uint64_t generation = r.generation();
  for (int i = 0; i < 6000 && (list.passes < passes || list.generation != generation); ++i) {
    if (!r.outliers(list, version)) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return list;
}

TEST(ProgressiveRenderer, PublishesTheOutliersOfAStandaloneRender) {
  const RenderSettings settings = small(IntegratorKind::Bpt, 7);
  ProgressiveRenderer renderer(sharedCornellBox(), settings, 2);
  renderer.setOutlierCount(6);
  renderer.setTargetSpp(5);
  const OutlierList list = settledOutliers(renderer, 5);
  ASSERT_EQ(list.passes, 5u);
  ASSERT_LT(list.firstPass, 5u);
  EXPECT_EQ(list.settings, settings);
  EXPECT_EQ(list.generation, renderer.generation());
  RenderSession session(*sharedCornellBox(), settings);
  for (uint64_t i = 0; i < list.firstPass; ++i) session.renderPass();
  session.setOutlierCount(6);
  for (uint64_t i = list.firstPass; i < 5; ++i) session.renderPass();
  const std::vector<Outlier> expected = session.outliers();
  ASSERT_EQ(list.top.size(), expected.size());
  ASSERT_EQ(expected.size(), 6u);
  for (size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(list.top[i].luminance, expected[i].luminance) << i;
    EXPECT_EQ(list.top[i].id.x, expected[i].id.x) << i;
    EXPECT_EQ(list.top[i].id.y, expected[i].id.y) << i;
    EXPECT_EQ(list.top[i].id.sample, expected[i].id.sample) << i;
    EXPECT_EQ(list.top[i].technique.index(), expected[i].technique.index()) << i;
  }

  // A new generation: an empty list first, then its own from its first pass.
  RenderSettings other = settings;
  other.seed = 8;
  renderer.setTargetSpp(2);
  ASSERT_TRUE(renderer.setSettings(other));
  const OutlierList next = settledOutliers(renderer, 2);
  EXPECT_EQ(next.generation, renderer.generation());
  EXPECT_EQ(next.firstPass, 0u);
  EXPECT_EQ(next.settings, other);
  EXPECT_FALSE(next.top.empty());
}

TEST(ProgressiveRenderer, ThePathTracerPublishesNoOutliers) {
  ProgressiveRenderer renderer(sharedCornellBox(), small(IntegratorKind::Pt, 9), 2);
  renderer.setOutlierCount(4);
  renderer.setTargetSpp(2);
  ASSERT_TRUE(renderer.waitForSpp(2, 60.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  OutlierList list;
  uint64_t version = 0;
  renderer.outliers(list, version);
  EXPECT_TRUE(list.top.empty());
  EXPECT_EQ(list.passes, 0u);
}

}  // namespace
}  // namespace pathlab
