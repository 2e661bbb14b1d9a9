// Metropolis light transport (core/mlt/metropolis.h) against closed forms and the bidirectional
// tracer: the furnace's geometric series for both variants and several heuristics (the image
// mean is the bootstrap's b there), region by region agreement with BPT on the Cornell box, the
// technique set restricting multiplexed chains, and the same image for the same seed at any
// thread count. A Metropolis render's passes are not independent, so standard errors come from
// independent renders (seeds) instead.
#include "core/render/render_session.h"
#include "core/render/sample_inspection.h"
#include "core/scene/gltf_loader.h"
#include "tests/support/image_means.h"
#include "tests/support/region_estimate.h"
#include "tests/support/test_scenes.h"

#include <gtest/gtest.h>

#include <iostream>
#include <tbb/global_control.h>

#include <cmath>
#include <string>

namespace pathlab {
namespace {

std::string mltAssetPath(const std::string& name) { return std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name; }

// The furnace of every test here: albedo rho, emission Le, paths of at most K edges; every pixel
// sees Le (1 - rho^K) / (1 - rho).
constexpr float kMltFurnaceRho = 0.6f, kMltFurnaceLe = 0.7f;
constexpr int kMltFurnaceLength = 5;
double mltFurnaceRadiance() { return kMltFurnaceLe * (1.0 - std::pow(kMltFurnaceRho, kMltFurnaceLength)) / (1.0 - kMltFurnaceRho); }

RenderSettings mltSettings(int size, int maxLength, MltVariant variant) {
  RenderSettings s;
  s.width = s.height = size;
  s.maxLength = maxLength;
  s.integrator = IntegratorKind::Mlt;
  s.mlt.variant = variant;
  s.mlt.chains = 64;
  s.mlt.bootstrap = 4000;
  return s;
}

struct MltFurnaceCase {
  MltVariant variant;
  MisHeuristic heuristic;
};

class MetropolisFurnace : public ::testing::TestWithParam<MltFurnaceCase> {};

// Every pixel sees Le (1 - rho^K) / (1 - rho) at maximum length K.
TEST_P(MetropolisFurnace, MatchesGeometricSeries) {
  Scene scene(test::furnace(kMltFurnaceRho, kMltFurnaceLe));
  const int K = kMltFurnaceLength;
  RenderSettings s = mltSettings(12, K, GetParam().variant);
  s.mis.heuristic = GetParam().heuristic;
  const test::MeanEstimate m = test::seedMeans(scene, s, 24, 2, 100);
  const double expected = mltFurnaceRadiance();
  EXPECT_LT(std::abs(m.zScore(expected)), test::kMaxZ) << "mean " << m.mean << " expected " << expected << " se "
                                                       << m.standardError;
  EXPECT_LT(m.standardError, 0.02 * expected);
}

INSTANTIATE_TEST_SUITE_P(
    Variants, MetropolisFurnace,
    ::testing::Values(MltFurnaceCase{MltVariant::Multiplexed, MisHeuristic::Balance},
                      MltFurnaceCase{MltVariant::Multiplexed, MisHeuristic::Power},
                      MltFurnaceCase{MltVariant::Multiplexed, MisHeuristic::Off},
                      MltFurnaceCase{MltVariant::PrimarySpace, MisHeuristic::Balance}),
    [](const auto& info) {
      return std::string(mltVariantName(info.param.variant)) + "_" + misHeuristicName(info.param.heuristic);
    });

// Region means over independent renders (one sample per seed) of `passes` passes each.
test::RegionMeans mltSeedRegionMeans(const Scene& scene, RenderSettings s, int seeds, int passes,
                                  const test::PixelLabels& labels, uint64_t firstSeed) {
  std::vector<std::array<test::RunningStats, 3>> region(static_cast<size_t>(labels.count));
  std::array<test::RunningStats, 3> whole;
  test::RegionMeans out;
  for (int seed = 0; seed < seeds; ++seed) {
    s.seed = firstSeed + static_cast<uint64_t>(seed);
    RenderSession session(scene, s);
    for (int i = 0; i < passes; ++i) session.renderPass();
    out.discarded += session.counters().discarded();
    const Image img = session.image();
    std::vector<std::array<double, 3>> sum(region.size(), {0, 0, 0});
    std::vector<int> count(region.size(), 0);
    std::array<double, 3> all{0, 0, 0};
    int allCount = 0;
    for (size_t p = 0; p < labels.label.size(); ++p) {
      const int l = labels.label[p];
      if (l < 0) continue;
      ++count[static_cast<size_t>(l)], ++allCount;
      for (int c = 0; c < 3; ++c) {
        sum[static_cast<size_t>(l)][static_cast<size_t>(c)] += img.rgb[3 * p + static_cast<size_t>(c)];
        all[static_cast<size_t>(c)] += img.rgb[3 * p + static_cast<size_t>(c)];
      }
    }
    for (size_t l = 0; l < region.size(); ++l)
      for (size_t c = 0; c < 3; ++c) region[l][c].add(sum[l][c] / count[l]);
    for (size_t c = 0; c < 3; ++c) whole[c].add(all[c] / allCount);
  }
  for (const auto& r : region) out.region.push_back({r[0].estimate(), r[1].estimate(), r[2].estimate()});
  out.whole = {whole[0].estimate(), whole[1].estimate(), whole[2].estimate()};
  return out;
}

struct MltAgreementCase {
  MltVariant variant;
  const char* techniques;
  int direct = 0;  // MltOptions::directLength
};

class MetropolisAgreement : public ::testing::TestWithParam<MltAgreementCase> {};

// Metropolis (32 independent renders of 8 passes, seeds from firstSeed) against BPT with the same
// settings (its bptPasses passes are independent samples, seed bptSeed), region by region in 2 x 2
// regions; power: the whole image's standard error below maxRelativeSe of its mean.
void expectMltAgreesWithBpt(const Scene& scene, const RenderSettings& mlt, int bptPasses, uint64_t firstSeed,
                            uint64_t bptSeed, double maxRelativeSe) {
  RenderSettings bpt = mlt;
  bpt.integrator = IntegratorKind::Bpt;
  bpt.seed = bptSeed;
  const test::PixelLabels labels = test::gridLabels(mlt.width, mlt.height, 2, 2);
  const test::RegionMeans a = mltSeedRegionMeans(scene, mlt, 32, 8, labels, firstSeed);
  const test::RegionMeans b = test::renderRegionMeans(scene, bpt, bptPasses, labels);
  EXPECT_EQ(a.discarded, 0u);
  const test::Agreement agreement = test::compareRegions(a, b);
  const double threshold = test::bonferroniZ(1e-3, agreement.comparisons);
  std::cout << "mlt vs bpt: max |z| " << agreement.maxAbsZ << " (" << agreement.worst << "), threshold " << threshold
            << "\n";
  EXPECT_LT(agreement.maxAbsZ, threshold) << agreement.worst;
  EXPECT_LT(a.whole[0].standardError, maxRelativeSe * a.whole[0].mean);
}

// The Cornell box in 2 x 2 regions: Metropolis (32 independent renders) against BPT with the same
// technique set (its passes are independent samples).
TEST_P(MetropolisAgreement, CornellBoxRegionsAgreeWithBpt) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  RenderSettings mlt = mltSettings(16, 6, GetParam().variant);
  mlt.techniques = TechniqueSet::parse(GetParam().techniques);
  mlt.mlt.directLength = GetParam().direct;
  expectMltAgreesWithBpt(scene, mlt, 2048, 1000, 7, 0.02);
}

INSTANTIATE_TEST_SUITE_P(Variants, MetropolisAgreement,
                         ::testing::Values(MltAgreementCase{MltVariant::Multiplexed, "all"},
                                           MltAgreementCase{MltVariant::PrimarySpace, "all"},
                                           MltAgreementCase{MltVariant::Multiplexed, "s=0;t=1"},
                                           // The short paths by BPT beside the chains, and every length by it.
                                           MltAgreementCase{MltVariant::Multiplexed, "all", 2},
                                           MltAgreementCase{MltVariant::PrimarySpace, "all", 2},
                                           MltAgreementCase{MltVariant::Multiplexed, "s=0;t=1", 6}),
                         [](const auto& info) {
                           return std::string(mltVariantName(info.param.variant)) +
                                  (std::string(info.param.techniques) == "all" ? "_all" : "_subset") +
                                  (info.param.direct ? "_direct" + std::to_string(info.param.direct) : "");
                         });

// Heterogeneous media under Metropolis (issue 35): the smoke scene's density grid, delta tracking
// seeded per segment from two of the chain's primary coordinates (media_step.cpp), against BPT.
TEST(MetropolisMedia, SmokeRegionsAgreeWithBpt) {
  Scene scene(loadGltf(mltAssetPath("smoke.gltf")));
  ASSERT_NE(scene.mediumGrid(0), nullptr);
  expectMltAgreesWithBpt(scene, mltSettings(12, 4, MltVariant::Multiplexed), 1024, 3000, 9, 0.03);
}

// A multiplexed chain never proposes a technique the set leaves out, and proposes every one it
// keeps.
TEST(Metropolis, MultiplexedChainsProposeOnlyEnabledTechniques) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  RenderSettings s = mltSettings(16, 4, MltVariant::Multiplexed);
  s.techniques = TechniqueSet::parse("s=0;t=1;2,2");
  RenderSession session(scene, s);
  for (int i = 0; i < 8; ++i) session.renderPass();
  const MltStats& stats = session.metropolis()->stats();
  EXPECT_EQ(stats.proposed, 8u * 16u * 16u);
  EXPECT_GT(stats.accepted, 0u);
  EXPECT_GT(stats.largeProposed, 0u);
  for (const Technique x : techniquesUpTo(4)) {
    const uint64_t proposed = stats.proposedByTechnique[x.index()];
    if (s.techniques.contains(x)) EXPECT_GT(proposed, 0u) << x.s << "," << x.t;
    else EXPECT_EQ(proposed, 0u) << x.s << "," << x.t;
  }
}

TEST(Metropolis, SameSeedSameImageAtAnyThreadCount) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  for (const MltVariant variant : {MltVariant::Multiplexed, MltVariant::PrimarySpace})
  for (const int direct : {0, 2}) {
    RenderSettings s = mltSettings(16, 5, variant);
    s.mlt.directLength = direct;
    auto render = [&](int threads, uint64_t seed) {
      const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
      s.seed = seed;
      RenderSession session(scene, s);
      for (int i = 0; i < 3; ++i) session.renderPass();
      return session.image().rgb;
    };
    const std::vector<float> one = render(1, 3);
    EXPECT_EQ(one, render(2, 3)) << mltVariantName(variant) << " direct " << direct;
    EXPECT_NE(one, render(2, 4)) << mltVariantName(variant) << " direct " << direct;
  }
}

// Large steps are independent samples of f, so b's estimate (and with it the image's brightness)
// keeps improving as the chains run, past what the bootstrap alone gives; in the furnace the
// image mean is b itself, so it is tested against the closed form with b's standard error.
TEST(Metropolis, LargeStepsRefineTheNormalisation) {
  Scene scene(test::furnace(kMltFurnaceRho, kMltFurnaceLe));
  const int K = kMltFurnaceLength;
  RenderSettings s = mltSettings(12, K, MltVariant::Multiplexed);
  s.mlt.bootstrap = 200;
  s.seed = 31;
  RenderSession session(scene, s);
  session.renderPass();
  const double afterBootstrap = session.metropolis()->normalisationError();
  for (int i = 0; i < 99; ++i) session.renderPass();
  const Metropolis& m = *session.metropolis();
  // 100 passes of 144 mutations, 30 % large steps: about 4300 samples beside the bootstrap's 1000.
  EXPECT_LT(m.normalisationError(), 0.6 * afterBootstrap);
  double sum = 0.0;
  const Image img = session.image();
  for (float v : img.rgb) sum += v;
  const double mean = sum / static_cast<double>(img.rgb.size());
  EXPECT_NEAR(mean, m.normalisation(), 1e-4 * m.normalisation());
  const double expected = mltFurnaceRadiance();
  EXPECT_LT(std::abs(mean - expected) / m.normalisationError(), test::kMaxZ)
      << "mean " << mean << " expected " << expected << " se " << m.normalisationError();
}

// Hostile sizes: a 1 x 1 image (fewer pixels than lengths: every chain still moves every pass) and
// a bootstrap of one sample per length (most lengths start from a zero sample and find their
// light by large steps) still converge to the furnace's closed form.
TEST(Metropolis, OnePixelAndABootstrapOfOneStillConverge) {
  Scene scene(test::furnace(kMltFurnaceRho, kMltFurnaceLe));
  const int K = kMltFurnaceLength;
  RenderSettings s = mltSettings(1, K, MltVariant::Multiplexed);
  s.mlt.bootstrap = 1;
  const test::MeanEstimate m = test::seedMeans(scene, s, 24, 200, 500);
  const double expected = mltFurnaceRadiance();
  EXPECT_LT(std::abs(m.zScore(expected)), test::kMaxZ) << "mean " << m.mean << " expected " << expected << " se "
                                                       << m.standardError;
  EXPECT_LT(m.standardError, 0.05 * expected);
}

// Where the chains spend their time: with one length (or PSSMLT's one histogram) the image's
// luminance is b times the chains' density, pixel by pixel, and the density averages one over the
// pixels (every contribution lands on the film: camera estimates and the lens's splats alike).
TEST(Metropolis, TheImageIsBTimesTheChainDensity) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  for (const MltVariant variant : {MltVariant::Multiplexed, MltVariant::PrimarySpace}) {
    RenderSettings s = mltSettings(16, 4, variant);
    s.techniques = TechniqueSet::parse("k=3");  // one length: one b
    RenderSession session(scene, s);
    for (int i = 0; i < 4; ++i) session.renderPass();
    const Metropolis& m = *session.metropolis();
    const std::vector<float> density = m.chainDensity();
    ASSERT_EQ(density.size(), 256u);
    const Image image = session.image();
    double mean = 0.0, lit = 0.0;
    for (size_t p = 0; p < density.size(); ++p) {
      const double y = luminance(Spectrum(image.rgb[3 * p], image.rgb[3 * p + 1], image.rgb[3 * p + 2]));
      EXPECT_NEAR(y, m.normalisation() * density[p], 1e-5 * (y + 1e-6)) << mltVariantName(variant) << " pixel " << p;
      mean += density[p] / 256.0;
      lit += density[p] > 0.f;
    }
    EXPECT_NEAR(mean, 1.0, 1e-5) << mltVariantName(variant);
    EXPECT_GT(lit, 128) << mltVariantName(variant);  // the chains went over most of the image
  }
}

// The chains the viewer's 3D view draws (Metropolis::setWatchedChains): each watched chain's
// current path and last proposals are replays of the very states the chain evaluated (the same
// target, bit for bit, the same technique), an MMLT path has its length's vertices from the light
// to the lens split at s, and watching changes nothing of the image.
TEST(Metropolis, WatchedChainsAreReplaysOfTheirStates) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  for (const MltVariant variant : {MltVariant::Multiplexed, MltVariant::PrimarySpace}) {
    const std::string name = mltVariantName(variant);
    RenderSettings s = mltSettings(16, 5, variant);
    auto render = [&](int watch, std::vector<MltWatchedChain>* watched) {
      RenderSession session(scene, s);
      session.metropolis()->setWatchedChains(watch);
      for (int i = 0; i < 3; ++i) session.renderPass();
      if (watched) *watched = session.metropolis()->summary().watched;
      return session.image().rgb;
    };
    std::vector<MltWatchedChain> watched;
    EXPECT_EQ(render(6, &watched), render(0, nullptr)) << name;
    ASSERT_EQ(watched.size(), 6u) << name;
    const Camera camera(scene.cameraDesc(), s.width, s.height);
    int moves = 0, accepted = 0, lit = 0;
    for (const MltWatchedChain& w : watched) {
      // 64 chains share 256 mutations a pass: 4 each, all of them in the trail.
      EXPECT_EQ(w.moves.size(), 4u) << name;
      EXPECT_EQ(w.current.f, w.chainF) << name << " chain " << w.chain;
      const MltChainPath* last = nullptr;
      for (const MltChainMove& m : w.moves) {
        EXPECT_EQ(m.proposal.f, m.chainF) << name << " chain " << w.chain;
        ++moves, accepted += m.accepted;
        if (m.accepted) last = &m.proposal;
      }
      if (last) {
        EXPECT_EQ(last->camera, w.current.camera) << name;  // the last accepted move is where it is
      }
      const MltChainPath& p = w.current;
      if (!(p.f > 0.f)) continue;
      ++lit;
      ASSERT_FALSE(p.camera.empty());
      EXPECT_LT(glm::length(p.camera.front() - camera.position()), 1e-4f) << name;  // from the lens
      if (variant == MltVariant::Multiplexed) {
        EXPECT_EQ(p.technique.length(), w.length) << name;
        EXPECT_EQ(p.light.size(), static_cast<size_t>(p.technique.s)) << name;
        EXPECT_EQ(p.light.size() + p.camera.size(), static_cast<size_t>(w.length) + 1) << name;
        EXPECT_EQ(p.connected, p.technique.s >= 1) << name;
      } else {
        EXPECT_FALSE(p.light.empty()) << name;  // the sample's light subpath starts on the lamp
      }
    }
    EXPECT_EQ(moves, 24) << name;
    EXPECT_GT(accepted, 0) << name;
    EXPECT_GT(lit, 3) << name;
  }
}

// `pathlab inspect` on an MLT render: a chain's state replayed from its primary numbers is the
// state the chain holds (its target and technique), after the bootstrap and after passes; the
// numbers it read are in [0, 1), and its contribution is where the trace's record lands.
TEST(Metropolis, ReplayedChainIsTheChainsState) {
  Scene scene(loadGltf(mltAssetPath("cornell-box.gltf")));
  for (const MltVariant variant : {MltVariant::Multiplexed, MltVariant::PrimarySpace}) {
    const std::string name = mltVariantName(variant);
    RenderSettings s = mltSettings(16, 5, variant);
    s.mlt.chains = 12;
    RenderSession session(scene, s);
    session.metropolis()->setWatchedChains(kMaxMltWatchedChains);  // every one (12, and one more a length may add)
    for (int pass = 0; pass < 3; ++pass) {
      session.renderPass();
      const Metropolis& m = *session.metropolis();
      const std::vector<MltWatchedChain> watched = m.summary().watched;
      ASSERT_EQ(watched.size(), m.chainCount()) << name;
      for (const MltWatchedChain& w : watched) {
        const MltChainState state = m.replayChain(static_cast<size_t>(w.chain));
        EXPECT_EQ(state.f, w.chainF) << name << " chain " << w.chain;
        EXPECT_EQ(state.length, w.length) << name;
        if (variant == MltVariant::Multiplexed) {
          EXPECT_EQ(state.technique.s, w.current.technique.s) << name;
          EXPECT_EQ(state.technique.t, w.current.technique.t) << name;
          EXPECT_LE(state.contributions.size(), 1u) << name;
        }
        EXPECT_FALSE(state.numbers[0].empty()) << name;  // the technique's choice, the film position
        for (const std::vector<float>& stream : state.numbers)
          for (const float u : stream) {
            EXPECT_GE(u, 0.f);
            EXPECT_LT(u, 1.f);
          }
      }
    }
    // Through the session: the trace's one record (MMLT) is the chain's technique.
    const SampleInspection in = inspectChain(session, 5, 3);
    ASSERT_TRUE(in.chain.has_value()) << name;
    EXPECT_EQ(in.sample, 3u);
    if (variant == MltVariant::Multiplexed) {
      ASSERT_EQ(in.trace.records.size(), 1u) << name;
      EXPECT_EQ(in.trace.records[0].s, in.chain->technique.s) << name;
    }
    EXPECT_THROW(inspectChain(session, session.metropolis()->chainCount(), 3), std::invalid_argument) << name;
  }
}

}  // namespace
}  // namespace pathlab
