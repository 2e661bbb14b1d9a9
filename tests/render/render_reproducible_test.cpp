// The same seed gives the same image bit for bit at 1, 2 and 16 threads: the light-tracing splats
// of a pass are summed in a fixed order of work items (pass_tiles.h), whatever thread rendered
// which item and whenever it finished; so are the pyramid's splats and the technique maps'. Also
// in the ThreadSanitizer binary (pathlab_thread_tests), where TBB runs serially: there it checks
// the pipeline's hand-over of the splat buffers.
#include "core/render/pass_tiles.h"
#include "core/render/render_session.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <bit>
#include <string>
#include <vector>

namespace pathlab {
namespace reproducible_test {

Scene bundled(const std::string& name) { return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf")); }

RenderSettings settings(IntegratorKind integrator) {
  RenderSettings s;
  s.width = 64;
  s.height = 48;
  s.maxLength = 6;
  s.seed = 11;
  s.integrator = integrator;
  return s;
}

// Every bit a render produces: the image, and with a pyramid each technique's weighted and
// unweighted image and the technique maps' sampleable luminance.
std::vector<uint32_t> bits(const RenderSession& session) {
  std::vector<uint32_t> out;
  auto add = [&](const std::vector<float>& values) {
    for (float v : values) out.push_back(std::bit_cast<uint32_t>(v));
  };
  add(session.image().rgb);
  if (session.hasPyramid())
    for (int k = 1; k <= session.settings().pyramidLength; ++k)
      for (int s = 0; s <= k; ++s) {
        const int t = k + 1 - s;
        add(session.techniqueImage({s, t}, false).rgb);
        add(session.techniqueImage({s, t}, true).rgb);
        if (session.settings().techniqueMaps) add(session.sampleableLuminance({s, t}));
      }
  return out;
}

// Renders `passes` passes on exactly `threads` threads (an arena of that many slots, and as many
// workers allowed: on a 2-core machine 16 threads take turns).
std::vector<uint32_t> render(const Scene& scene, const RenderSettings& s, int threads, int passes = 3) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<size_t>(threads));
  tbb::task_arena arena(threads);
  return arena.execute([&] {
    RenderSession session(scene, s);
    for (int i = 0; i < passes; ++i) EXPECT_TRUE(session.renderPass());
    EXPECT_EQ(session.counters().cameraSamples, static_cast<uint64_t>(passes) * 64u * 48u);
    return bits(session);
  });
}

void expectSameAtAnyThreadCount(const Scene& scene, const RenderSettings& s, const char* what, int passes = 3) {
  const std::vector<uint32_t> one = render(scene, s, 1, passes);
  // Not all black: the comparison means something.
  EXPECT_TRUE(std::any_of(one.begin(), one.end(), [](uint32_t b) { return b != 0; })) << what;
  for (int threads : {2, 16}) {
    const std::vector<uint32_t> many = render(scene, s, threads, passes);
    ASSERT_EQ(many.size(), one.size()) << what;
    size_t differ = 0;
    for (size_t i = 0; i < one.size(); ++i) differ += one[i] != many[i];
    EXPECT_EQ(differ, 0u) << what << ": " << differ << " of " << one.size() << " values differ at " << threads
                          << " threads from 1 thread";
  }
}

TEST(RenderSessionReproducible, BidirectionalCornellBox) {
  expectSameAtAnyThreadCount(bundled("cornell-box"), settings(IntegratorKind::Bpt), "cornell-box bpt");
}

TEST(RenderSessionReproducible, PyramidAndTechniqueMapsWithLightTracing) {
  RenderSettings s = settings(IntegratorKind::Bpt);
  s.pyramidLength = 3;
  s.techniqueMaps = true;
  expectSameAtAnyThreadCount(bundled("caustic"), s, "caustic bpt, pyramid 3 and technique maps");
}

TEST(RenderSessionReproducible, LightTracerAndPathTracer) {
  const Scene box = bundled("cornell-box");
  expectSameAtAnyThreadCount(box, settings(IntegratorKind::Lt), "cornell-box lt");
  expectSameAtAnyThreadCount(bundled("fog"), settings(IntegratorKind::Bpt), "fog bpt");
  expectSameAtAnyThreadCount(box, settings(IntegratorKind::Pt), "cornell-box pt");
}

// Variance-aware MIS weighs each pass with factors estimated from the passes before it, the
// splats' share summed in the work items' order: past the pilot passes the factors, so the images,
// are the same bits at any thread count (connections, and merges with their correlated photons).
TEST(RenderSessionReproducible, VarianceAwareMis) {
  RenderSettings s = settings(IntegratorKind::Bpt);
  s.mis.heuristic = MisHeuristic::VarianceAware;
  const int passes = kVarianceAwarePilotPasses + 3;
  expectSameAtAnyThreadCount(bundled("cornell-box"), s, "cornell-box bpt variance-aware", passes);
  s.techniques = TechniqueSet::parse("all;m=all");
  expectSameAtAnyThreadCount(bundled("caustic"), s, "caustic vcm variance-aware", passes);
}

// Optimal MIS solves its coefficients after 4 and 8 passes from sums whose splats are added in the
// work items' order: the corrected images are the same bits at any thread count.
TEST(RenderSessionReproducible, OptimalMis) {
  RenderSettings s = settings(IntegratorKind::Bpt);
  s.mis.heuristic = MisHeuristic::Optimal;
  expectSameAtAnyThreadCount(bundled("cornell-box"), s, "cornell-box bpt optimal", 10);
}

// --light-paths auto chooses F after 4 and 8 passes from moments whose splats are summed in the
// work items' order and from ray counts: the choices, so the images, are the same at any thread
// count.
TEST(RenderSessionReproducible, LightPathsAuto) {
  RenderSettings s = settings(IntegratorKind::Bpt);
  s.lightPathsAuto = true;
  LoadOptions load;
  load.defaultLight = true;  // as `pathlab render` lights it: F moves to 1/16 after 4 passes
  const Scene scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/environment.gltf", load));
  expectSameAtAnyThreadCount(scene, s, "environment bpt light-paths auto", 10);
}

// The work items cover the film once, in bands of at most the asked-for pixels (a row at least).
TEST(RenderSessionReproducible, PassTilesCoverTheFilmOnce) {
  for (const auto& [w, h] : {std::pair{64, 48}, std::pair{1, 1}, std::pair{17, 300}, std::pair{1920, 1080}}) {
    std::vector<int> covered(static_cast<size_t>(w * h), 0);
    for (const PassTile& t : passTiles(w, h)) {
      EXPECT_TRUE(t.pixels() <= 1024 || t.y1 - t.y0 == 1) << w << "x" << h;
      for (int y = t.y0; y < t.y1; ++y)
        for (int x = t.x0; x < t.x1; ++x) ++covered[static_cast<size_t>(y * w + x)];
    }
    EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; })) << w << "x" << h;
  }
}

}  // namespace reproducible_test
}  // namespace pathlab
