// Interleaved pass schedules (what the ranks of an MPI job render): sessions given passes r, r + N,
// ... and combined through sums() and addForeignPasses hold exactly the samples of one session
// rendering every pass, up to the order of the additions.
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <memory>

namespace pathlab {
namespace {

// 24 x 16; the bidirectional tracer also keeps the pyramid up to length 3 and its sampleable films.
RenderSettings smallSettings(IntegratorKind integrator) {
  RenderSettings s;
  s.integrator = integrator;
  s.width = 24, s.height = 16, s.seed = 11;
  const bool bidirectional = integrator != IntegratorKind::Pt;
  s.pyramidLength = bidirectional ? 3 : 0;
  s.techniqueMaps = bidirectional;
  return s;
}

// Each value within 1e-6 of the other, relative: the same samples summed in another order.
void expectSameValues(const std::vector<float>& a, const std::vector<float>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-6f * std::max(std::abs(a[i]), std::abs(b[i])) + 1e-30f) ++differing;
  EXPECT_EQ(differing, 0u) << what << ": values differ beyond summation order";
}

// N sessions with schedules (r, N), P passes each, added into the first: one session of N P passes.
void expectInterleavedEqualsWhole(IntegratorKind integrator) {
  tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  const RenderSettings settings = smallSettings(integrator);
  constexpr uint64_t kRanks = 3, kPasses = 2;
  RenderSession whole(scene, settings);
  for (uint64_t i = 0; i < kRanks * kPasses; ++i) whole.renderPass();

  std::vector<std::unique_ptr<RenderSession>> ranks;
  for (uint64_t r = 0; r < kRanks; ++r) {
    ranks.push_back(std::make_unique<RenderSession>(scene, settings, PassSchedule{r, kRanks}));
    for (uint64_t i = 0; i < kPasses; ++i) ranks.back()->renderPass();
  }
  RenderSession& leader = *ranks[0];
  std::vector<std::span<double>> into = leader.sums();
  for (uint64_t r = 1; r < kRanks; ++r) {
    std::vector<std::span<double>> from = ranks[r]->sums();
    ASSERT_EQ(from.size(), into.size());
    for (size_t k = 0; k < into.size(); ++k) {
      ASSERT_EQ(from[k].size(), into[k].size());
      for (size_t i = 0; i < into[k].size(); ++i) into[k][i] += from[k][i];
    }
    leader.addForeignPasses(ranks[r]->passes(), ranks[r]->counters());
  }

  EXPECT_EQ(leader.passes(), kPasses);
  EXPECT_EQ(leader.film().samplesPerPixel(), whole.film().samplesPerPixel());
  EXPECT_EQ(leader.film().lightSubpaths(), whole.film().lightSubpaths());
  EXPECT_EQ(leader.counters().cameraSamples, whole.counters().cameraSamples);
  EXPECT_EQ(leader.counters().totalRays(), whole.counters().totalRays());
  expectSameValues(leader.image().rgb, whole.image().rgb, "image");
  if (integrator == IntegratorKind::Pt) return;
  for (int k = 1; k <= settings.pyramidLength; ++k)
    for (int s = 0; s <= k; ++s) {
      const int t = k + 1 - s;
      for (bool unweighted : {false, true})
        expectSameValues(leader.techniqueImage({s, t}, unweighted).rgb, whole.techniqueImage({s, t}, unweighted).rgb,
                         unweighted ? "unweighted technique" : "weighted technique");
      expectSameValues(leader.sampleableLuminance({s, t}), whole.sampleableLuminance({s, t}), "sampleable luminance");
    }
}

TEST(PassSchedule, InterleavedPathTracerSessionsEqualOneSession) { expectInterleavedEqualsWhole(IntegratorKind::Pt); }

// Bidirectional: camera sums, the light tracer's splats and the pyramid's films.
TEST(PassSchedule, InterleavedBidirectionalSessionsEqualOneSession) {
  expectInterleavedEqualsWhole(IntegratorKind::Bpt);
}

TEST(PassSchedule, PassIndicesAreInterleaved) {
  EXPECT_EQ((PassSchedule{}.pass(5)), 5u);
  EXPECT_EQ((PassSchedule{1, 4}.pass(0)), 1u);
  EXPECT_EQ((PassSchedule{1, 4}.pass(2)), 9u);
  Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/cornell-box.gltf"));
  EXPECT_THROW(RenderSession(scene, smallSettings(IntegratorKind::Pt), PassSchedule{0, 0}), std::invalid_argument);
}

}  // namespace
}  // namespace pathlab
