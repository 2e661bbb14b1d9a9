// The technique pyramid and isolation (issue 3): the weighted shares of the enabled techniques
// sum to the full image, an isolated render equals its pyramid buffer, the unweighted techniques
// of one length estimate the same image (z-test over seeds), and the per-technique counters
// account for every connection.
#include "core/render/render_session.h"
#include "core/sampling/technique_label.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/statistics.h"

#include <gtest/gtest.h>

#include <stdexcept>

namespace pathlab {
namespace {

using test::RunningStats;

const Scene& cornellBox() {
  static const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  return scene;
}

RenderSettings pyramidSettings(int maxLength, int pyramidLength, uint64_t seed) {
  RenderSettings s;
  s.width = 20;
  s.height = 16;
  s.maxLength = maxLength;
  s.pyramidLength = pyramidLength;
  s.seed = seed;
  s.integrator = IntegratorKind::Bpt;
  return s;
}

double imageSum(const Image& img) {
  double sum = 0.0;
  for (float v : img.rgb) sum += v;
  return sum;
}

void expectImagesNear(const Image& a, const Image& b, double relative, const char* what) {
  ASSERT_EQ(a.rgb.size(), b.rgb.size());
  for (size_t i = 0; i < a.rgb.size(); ++i)
    ASSERT_NEAR(a.rgb[i], b.rgb[i], relative * std::max(std::abs(a.rgb[i]), std::abs(b.rgb[i])) + 1e-7)
        << what << " at value " << i;
}

// Veach 1997 eq. 10.9 with weights normalised over the enabled set: sum over (s, t) of
// w_{s,t} C_{s,t} is the image, so the weighted buffers of all techniques (when the pyramid
// covers every length) add up to the main film, pixel by pixel, in every heuristic and subset.
TEST(TechniquePyramid, WeightedSharesSumToTheImage) {
  for (const auto& [heuristic, spec] : {std::pair{MisHeuristic::Balance, "all"}, std::pair{MisHeuristic::Power, "all"},
                                        std::pair{MisHeuristic::Uniform, "s=0;s=1;2,2;3,1"},
                                        std::pair{MisHeuristic::Balance, "t=1;0,2;0,3;0,4"}}) {
    RenderSettings s = pyramidSettings(4, 4, 11);
    s.mis.heuristic = heuristic;
    s.techniques = TechniqueSet::parse(spec);
    RenderSession session(cornellBox(), s);
    for (int i = 0; i < 3; ++i) session.renderPass();
    const Image full = session.image();
    Image sum{full.width, full.height, std::vector<float>(full.rgb.size(), 0.f)};
    for (const Technique x : techniquesUpTo(4)) {
      const Image share = session.techniqueImage(x, false);
      for (size_t i = 0; i < sum.rgb.size(); ++i) sum.rgb[i] += share.rgb[i];
    }
    SCOPED_TRACE(spec);
    EXPECT_GT(imageSum(full), 0.0);
    expectImagesNear(full, sum, 1e-4, "sum of weighted shares vs image");
  }
}

// Isolation renders exactly the pyramid's buffer of that technique: each connection draws from
// a stream keyed by (sample, s, t), so what other techniques are evaluated does not matter.
TEST(TechniquePyramid, IsolatedRenderEqualsItsPyramidBuffer) {
  const RenderSettings base = pyramidSettings(4, 3, 12);
  RenderSession pyramid(cornellBox(), base);
  for (int i = 0; i < 2; ++i) pyramid.renderPass();
  for (const auto& [s, t] : {std::pair{0, 3}, std::pair{1, 2}, std::pair{2, 2}, std::pair{3, 1}, std::pair{1, 1}})
    for (bool unweighted : {false, true}) {
      RenderSettings iso = base;
      iso.pyramidLength = 0;
      iso.isolate = Isolation{s, t, unweighted};
      RenderSession session(cornellBox(), iso);
      for (int i = 0; i < 2; ++i) session.renderPass();
      SCOPED_TRACE(testing::Message() << "(" << s << "," << t << ")" << (unweighted ? " unweighted" : " weighted"));
      const Image expected = pyramid.techniqueImage({s, t}, unweighted);
      EXPECT_GT(imageSum(expected), 0.0);
      expectImagesNear(session.image(), expected, 1e-5, "isolated render vs pyramid buffer");
    }
}

// The same for merges: an isolated merge renders its pyramid buffer, weighted (among connections
// and merges) and unweighted; the unweighted one also when no merge is enabled (the pass's store
// is built for it alone). The merges of a pass find the same light vertices whatever else runs.
TEST(TechniquePyramid, IsolatedMergeEqualsItsPyramidBuffer) {
  RenderSettings base = pyramidSettings(4, 4, 12);
  base.techniques = TechniqueSet::parse("all;m=all");
  base.mergeRadius = 0.05f;  // 320 light subpaths a pass: a radius that finds some
  RenderSession pyramid(cornellBox(), base);
  for (int i = 0; i < 2; ++i) pyramid.renderPass();
  for (const Technique x : {Technique::merge(2, 2), Technique::merge(2, 3), Technique::merge(3, 2)})
    for (const bool connectionsOnly : {false, true})
      for (const bool unweighted : {false, true}) {
        if (connectionsOnly && !unweighted) continue;  // a disabled technique has no weighted share
        RenderSettings iso = base;
        iso.pyramidLength = 0;
        if (connectionsOnly) iso.techniques = TechniqueSet::all();
        iso.isolate = Isolation{x.s, x.t, unweighted, TechniqueKind::Merge};
        RenderSession session(cornellBox(), iso);
        for (int i = 0; i < 2; ++i) session.renderPass();
        SCOPED_TRACE(testing::Message() << techniqueLabel(x) << (unweighted ? " unweighted" : " weighted")
                                        << (connectionsOnly ? ", no merge enabled" : ""));
        const Image expected = pyramid.techniqueImage(x, unweighted);
        EXPECT_GT(imageSum(expected), 0.0);
        expectImagesNear(session.image(), expected, 1e-5, "isolated merge vs pyramid buffer");
      }
}

// Without delta components every technique of length k samples every path of length k, so all
// unweighted buffers of that length estimate the same image (Veach 1997 sec. 10.2). Compare the
// image sums of each unweighted technique with the sum of the weighted shares of its length, over
// independent seeds: z = (mean difference) / (its standard error), each seed one sample.
TEST(TechniquePyramid, UnweightedTechniquesOfOneLengthAgree) {
  constexpr int kLength = 3, kSeeds = 24, kPasses = 4;
  // Per technique (by index): the difference unweighted(s, t) - sum of weighted shares of its length.
  std::vector<RunningStats> diff(Technique::countUpTo(kLength));
  for (int seed = 0; seed < kSeeds; ++seed) {
    RenderSession session(cornellBox(), pyramidSettings(kLength, kLength, 100 + static_cast<uint64_t>(seed)));
    for (int i = 0; i < kPasses; ++i) session.renderPass();
    for (int k = 1; k <= kLength; ++k) {
      double weightedSum = 0.0;
      for (const Technique x : techniquesOfLength(k)) weightedSum += imageSum(session.techniqueImage(x, false));
      for (const Technique x : techniquesOfLength(k))
        diff[x.index()].add(imageSum(session.techniqueImage(x, true)) - weightedSum);
    }
  }
  // 9 comparisons: |z| < 4 has a family-wise false-alarm rate below 9 x 6.3e-5.
  for (const Technique x : techniquesUpTo(kLength)) {
    const auto e = diff[x.index()].estimate();
    SCOPED_TRACE(testing::Message() << "(" << x.s << "," << x.t << ") mean diff " << e.mean << " se "
                                    << e.standardError);
    ASSERT_GT(e.standardError, 0.0);
    EXPECT_LT(std::abs(e.zScore(0.0)), 4.0);
  }
}

// Every connection is tried and ends as zero, blocked or contributing; every shadow ray of a
// bidirectional render belongs to a connection that was blocked or contributed with s >= 1
// (s = 0 needs none), and the subpath walks trace the rest.
TEST(TechniqueCounters, EveryConnectionIsAccountedFor) {
  RenderSettings s = pyramidSettings(5, 0, 13);
  RenderSession session(cornellBox(), s);
  session.renderPass();
  const Counters& c = session.counters();
  uint64_t shadowRays = 0, tried = 0;
  for (const Technique x : techniquesUpTo(5)) {
    const TechniqueCounters& t = c.technique(x);
    EXPECT_EQ(t.tried, t.zero + t.blocked + t.contributed) << "(" << x.s << "," << x.t << ")";
    if (x.s == 0) EXPECT_EQ(t.blocked, 0u);
    else shadowRays += t.blocked + t.contributed;
    tried += t.tried;
  }
  EXPECT_EQ(c.shadowRays, shadowRays);
  EXPECT_GT(c.technique(2, 2).blocked, 0u);  // the boxes occlude some connections
  EXPECT_GT(c.technique(1, 1).tried, 0u);
  EXPECT_EQ(c.technique(1, 1).tried, c.cameraSamples);  // one light subpath per camera sample
  // Nothing of length 6 or more was tried at maximum length 5.
  EXPECT_EQ(c.technique(3, 4).tried, 0u);
  EXPECT_EQ(c.discarded(), 0u);
}

TEST(RenderSettingsValidation, RefusesWhatCannotBeRendered) {
  auto refused = [](auto edit) {
    RenderSettings s = pyramidSettings(4, 0, 0);
    edit(s);
    EXPECT_THROW(validateSettings(s), std::invalid_argument);
  };
  refused([](RenderSettings& s) { s.isolate = Isolation{3, 3}; });   // length 5 > 4
  refused([](RenderSettings& s) { s.isolate = Isolation{-1, 2}; });
  refused([](RenderSettings& s) { s.isolate = Isolation{0, 1}; });   // length 0
  refused([](RenderSettings& s) { s.isolate = Isolation{1, 1}; s.integrator = IntegratorKind::Pt; });
  refused([](RenderSettings& s) { s.isolate = Isolation{1, 2}; s.integrator = IntegratorKind::Lt; });
  refused([](RenderSettings& s) { s.pyramidLength = 5; });
  refused([](RenderSettings& s) { s.pyramidLength = 2; s.integrator = IntegratorKind::Pt; });
  refused([](RenderSettings& s) { s.maxLength = 12; s.pyramidLength = kMaxPyramidLength + 1; });
  refused([](RenderSettings& s) { s.width = s.height = 16384; s.pyramidLength = 4; });  // far beyond memory
  refused([](RenderSettings& s) { s.techniques = TechniqueSet::parse("0,2;3,3"); });  // (3,3): length 5 > 4
  refused([](RenderSettings& s) { s.techniques = TechniqueSet::withS(5); });  // no technique of length <= 4
  refused([](RenderSettings& s) { s.techniques = TechniqueSet(); });
  refused([](RenderSettings& s) { s.maxLength = kMaxBidirectionalLength + 1; });
  refused([](RenderSettings& s) { s.isolate = Isolation{1, 3, false, TechniqueKind::Merge}; });  // s < 2
  refused([](RenderSettings& s) { s.isolate = Isolation{3, 4, false, TechniqueKind::Merge}; });  // length 5 > 4
  refused([](RenderSettings& s) {
    s.isolate = Isolation{2, 2, true, TechniqueKind::Merge};
    s.integrator = IntegratorKind::Lt;
  });
  RenderSettings ok = pyramidSettings(4, 4, 0);
  ok.isolate = Isolation{2, 3, true};
  EXPECT_NO_THROW(validateSettings(ok));
  ok.isolate = Isolation{3, 3, true, TechniqueKind::Merge};  // length 4
  EXPECT_NO_THROW(validateSettings(ok));
  EXPECT_THROW(RenderSession(cornellBox(), [] {
                 RenderSettings s = pyramidSettings(4, 0, 0);
                 s.isolate = Isolation{9, 9};
                 return s;
               }()),
               std::invalid_argument);
}

// Replaying every pixel's sample (camera side plus its t = 1 splats) rebuilds the rendered
// film: the replay is the render, technique by technique.
TEST(RenderSession, ReplayOfEverySampleRebuildsTheBidirectionalImage) {
  RenderSettings s = pyramidSettings(5, 0, 21);
  RenderSession session(cornellBox(), s);
  session.renderPass();
  Film replayed(s.width, s.height);
  Counters c;
  SampleTrace trace;
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      EXPECT_TRUE(replayed.addSample(x, y, session.replaySample(x, y, 0, c, &replayed, &trace)));
      for (const TechniqueResult& r : trace.records) EXPECT_LE(r.s + r.t - 1, 5);
    }
  replayed.finishPass(1, lightSubpathsPerPass(replayed.pixelCount()));
  expectImagesNear(replayed.readout(), session.image(), 1e-5, "replayed vs rendered");
}

// The checkMis setting (on in debug builds) finds the weights a partition of unity on every path
// of every bundled scene, under each heuristic.
TEST(RenderSession, MisWeightsSumToOneOnEveryPathOfTheBundledScenes) {
  for (const char* name : {"cornell-box", "veach-mis", "bidir-lamp", "caustic"}) {
    const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
    for (MisHeuristic h : {MisHeuristic::Balance, MisHeuristic::Power, MisHeuristic::Uniform}) {
      RenderSettings s = pyramidSettings(8, 0, 22);
      s.mis.heuristic = h;
      s.checkMis = true;
      RenderSession session(scene, s);
      session.renderPass();
      EXPECT_GT(session.counters().misPartitionChecks, 100u) << name;
      EXPECT_EQ(session.counters().misPartitionFailures, 0u) << name << " " << misHeuristicName(h);
    }
  }
}

// A cancelled pass stops between tiles and leaves the pass count alone.
TEST(RenderSession, CancelledPassReportsIt) {
  RenderSession session(cornellBox(), pyramidSettings(4, 0, 0));
  std::atomic<bool> cancel{true};
  EXPECT_FALSE(session.renderPass(&cancel));
  EXPECT_EQ(session.passes(), 0u);
  EXPECT_EQ(session.counters().cameraSamples, 0u);
  cancel = false;
  EXPECT_TRUE(session.renderPass(&cancel));
  EXPECT_EQ(session.passes(), 1u);
}

}  // namespace
}  // namespace pathlab
