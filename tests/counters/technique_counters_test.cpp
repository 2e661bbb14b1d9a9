// Per-technique rays and time (issue 5, the viewer's technique table and `render --stats`):
// counters merge field by field; every shadow ray of a technique with s >= 1 ends blocked or
// contributing; the walks' rays are all the closest-hit rays; timing is off unless asked for and
// never starts a new generation of the progressive renderer.
#include "core/counters/counters.h"
#include "core/render/progressive_renderer.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

namespace pathlab {
namespace {

const Scene& countersCornellBox() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  return scene;
}

RenderSettings bpt() {
  RenderSettings s;
  s.width = 24;
  s.height = 16;
  s.maxLength = 5;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

TEST(TechniqueCounters, MergeEveryField) {
  Counters a, b;
  a.technique(1, 2).shadowRays = 3;
  a.technique(1, 2).nanoseconds = 100;
  a.cameraWalk = {10, 1000};
  a.lightWalk = {20, 2000};
  a.mergePass = {30, 300};
  a.mergeSearch = {0, 40};
  a.timedSamples = 5;
  b.technique(1, 2).shadowRays = 4;
  b.technique(1, 2).nanoseconds = 50;
  b.technique(2, 1).nanoseconds = 7;
  b.cameraWalk = {1, 1};
  b.lightWalk = {2, 2};
  b.mergePass = {3, 3};
  b.mergeSearch = {0, 4};
  b.timedSamples = 1;
  a += b;
  EXPECT_EQ(a.technique(1, 2).shadowRays, 7u);
  EXPECT_EQ(a.technique(1, 2).nanoseconds, 150u);
  EXPECT_EQ(a.technique(2, 1).nanoseconds, 7u);
  EXPECT_EQ(a.cameraWalk.rays, 11u);
  EXPECT_EQ(a.cameraWalk.nanoseconds, 1001u);
  EXPECT_EQ(a.lightWalk.rays, 22u);
  EXPECT_EQ(a.lightWalk.nanoseconds, 2002u);
  EXPECT_EQ(a.mergePass.rays, 33u);
  EXPECT_EQ(a.mergePass.nanoseconds, 303u);
  EXPECT_EQ(a.mergeSearch.nanoseconds, 44u);
  EXPECT_EQ(a.timedSamples, 6u);
  EXPECT_EQ(a.timedNanoseconds(), 1001u + 2002u + 303u + 44u + 150u + 7u);
}

TEST(TechniqueCounters, RaysOfEachTechniqueAndWalk) {
  RenderSession session(countersCornellBox(), bpt());
  for (int i = 0; i < 4; ++i) session.renderPass();
  const Counters& c = session.counters();
  uint64_t shadow = 0;
  for (const Technique x : techniquesUpTo(bpt().maxLength)) {
    const int s = x.s, t = x.t;
    const TechniqueCounters& tc = c.technique(s, t);
    shadow += tc.shadowRays;
    if (s == 0) {
      EXPECT_EQ(tc.shadowRays, 0u) << "(0," << t << ") traces no shadow ray";
    } else {
      // A connection traces its shadow ray only when it would contribute: it is then blocked or not.
      EXPECT_EQ(tc.shadowRays, tc.blocked + tc.contributed) << "(" << s << "," << t << ")";
      EXPECT_GT(tc.shadowRays, 0u) << "(" << s << "," << t << ")";
    }
  }
  EXPECT_EQ(shadow, c.shadowRays);
  EXPECT_EQ(c.cameraWalk.rays + c.lightWalk.rays, c.rays);
  EXPECT_GT(c.cameraWalk.rays, 0u);
  EXPECT_GT(c.lightWalk.rays, 0u);
  // Timing is off by default: nothing measured.
  EXPECT_EQ(c.timedNanoseconds(), 0u);
  EXPECT_EQ(c.timedSamples, 0u);
}

// With every technique enabled a connection's shadow ray is traced before its weight, except
// where the weight may be zero: a connection edge shorter than --min-connection (bidir_tracer.cpp).
// A large minimum makes such connections common; none of them may cost a shadow ray.
TEST(TechniqueCounters, ShortConnectionsTraceNoShadowRay) {
  RenderSettings settings = bpt();
  settings.checkMis = false;  // the release path: the shadow ray first where it may
  RenderSession plain(countersCornellBox(), settings);
  settings.mis.minConnection = 0.5f;  // half the scene's radius
  RenderSession excluding(countersCornellBox(), settings);
  for (int i = 0; i < 4; ++i) {
    plain.renderPass();
    excluding.renderPass();
  }
  uint64_t zeroPlain = 0, zeroExcluding = 0;
  for (const Technique x : techniquesUpTo(settings.maxLength)) {
    const int s = x.s, t = x.t;
    if (s == 0) continue;
    const TechniqueCounters& tc = excluding.counters().technique(s, t);
    EXPECT_EQ(tc.shadowRays, tc.blocked + tc.contributed) << "(" << s << "," << t << ")";
    zeroPlain += plain.counters().technique(s, t).zero;
    zeroExcluding += tc.zero;
  }
  // The same paths (same seed), of which the short connections now weigh zero.
  EXPECT_GT(zeroExcluding, zeroPlain + 100);
}

TEST(TechniqueCounters, TimingWhenAskedChangesNoCount) {
  RenderSession timed(countersCornellBox(), bpt()), untimed(countersCornellBox(), bpt());
  timed.setTiming(true);
  timed.renderPass();
  untimed.renderPass();
  const Counters& c = timed.counters();
  // One sample in eight, picked at random: 384 samples, 48 expected, standard deviation 6.5.
  EXPECT_GT(c.timedSamples, 16u);
  EXPECT_LT(c.timedSamples, 80u);
  EXPECT_GT(c.cameraWalk.nanoseconds, 0u);
  EXPECT_GT(c.lightWalk.nanoseconds, 0u);
  EXPECT_GT(c.technique(1, 2).nanoseconds, 0u);
  EXPECT_GT(c.technique(0, 2).nanoseconds, 0u);
  // The same samples: the same counts.
  for (size_t i = 0; i < c.techniques.size(); ++i) {
    EXPECT_EQ(c.techniques[i].tried, untimed.counters().techniques[i].tried);
    EXPECT_EQ(c.techniques[i].shadowRays, untimed.counters().techniques[i].shadowRays);
  }
  EXPECT_EQ(c.rays, untimed.counters().rays);
}

// Vertex merging's shared work has rows of its own: the merge pass's walks' rays (every ray is a
// walk's or the pass's), and, while timing, the pass's time, the range searches' and each merge's.
// Without merges there is none of it.
TEST(TechniqueCounters, MergingHasItsRaysAndTime) {
  RenderSettings vcm = bpt();
  vcm.techniques = TechniqueSet::parse("all;m=all");
  vcm.mergeRadius = 0.05f;  // 384 light subpaths: a radius that finds some of them
  vcm.mergeNonCaustic = 1.f;  // all of them kept
  for (const bool merges : {true, false}) {
    RenderSession session(countersCornellBox(), merges ? vcm : bpt());
    session.setTiming(true);
    for (int i = 0; i < 3; ++i) session.renderPass();
    const Counters& c = session.counters();
    EXPECT_EQ(c.cameraWalk.rays + c.lightWalk.rays + c.mergePass.rays, c.rays);
    uint64_t mergeTime = 0, mergeTries = 0;
    for (const Technique x : techniquesUpTo(vcm.maxLength, TechniqueFamilies::Merges)) {
      mergeTime += c.technique(x).nanoseconds;
      mergeTries += c.technique(x).tried;
    }
    if (merges) {
      EXPECT_GT(c.mergePass.rays, 0u);
      EXPECT_GT(c.mergePass.nanoseconds, 0u);
      EXPECT_GT(c.mergeSearch.nanoseconds, 0u);
      EXPECT_GT(mergeTries, 100u);
      EXPECT_GT(mergeTime, 0u);
    } else {
      EXPECT_EQ(c.mergePass.rays + c.mergePass.nanoseconds + c.mergeSearch.nanoseconds + mergeTime + mergeTries, 0u);
    }
  }
}

TEST(TechniqueCounters, TimingIsNoNewGeneration) {
  auto scene = std::make_shared<const Scene>(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  ProgressiveRenderer renderer(scene, bpt(), 2);
  renderer.setTargetSpp(2);
  ASSERT_TRUE(renderer.waitForSpp(2, 60.0));
  // The worker starts before the target is set and may have rendered more passes by then (a small
  // image under load): time the four passes after wherever it stopped.
  RenderSnapshot before;
  ASSERT_TRUE(renderer.snapshot(before));
  const uint64_t untimed = before.samplesPerPixel;
  const uint64_t generation = renderer.generation();
  renderer.setTiming(true);
  renderer.setTargetSpp(untimed + 4);
  ASSERT_TRUE(renderer.waitForSpp(untimed + 4, 60.0));
  EXPECT_EQ(renderer.generation(), generation);
  RenderSnapshot snap;
  ASSERT_TRUE(renderer.snapshot(snap));
  // The last four passes were timed, the previews and the passes before them not.
  EXPECT_GT(snap.counters.timedSamples, 0u);
  EXPECT_LT(snap.counters.timedSamples, snap.counters.cameraSamples);
  EXPECT_GT(snap.counters.timedNanoseconds(), 0u);
}

}  // namespace
}  // namespace pathlab
