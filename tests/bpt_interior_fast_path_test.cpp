// BidirTracer::runInterior, the interior connections' (s, t >= 2) fast path, promises what the
// general kernel (evaluate, run, SampleOutputs::add) gives: every sample's pixel estimate bit for
// bit, the same splats, and the same per-technique counters (tried, zero, blocked, contributed,
// shadow rays, discards), on every bundled scene, under every heuristic, with and without
// --min-connection (whose short connections it weighs before their shadow ray, as evaluate does)
// and with a pyramid that takes the short techniques back to the general path.
// BidirTracer::setInteriorFastPath(false) is the oracle.
#include "core/bpt/bidir_tracer.h"
#include "core/film/film.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <bit>

namespace pathlab {
namespace {

constexpr int kWidth = 24, kHeight = 18;

struct Run {
  std::vector<uint32_t> estimates;  // 3 floats' bits per sample
  std::vector<double> splats;
  Counters counters;
};

Run render(const Scene& scene, const BidirOptions& options, bool fastPath, bool withPyramid, int samples) {
  const Camera camera(scene.cameraDesc(), kWidth, kHeight);
  BidirTracer tracer(scene, camera, options);
  tracer.setInteriorFastPath(fastPath);
  Film film(kWidth, kHeight);
  TechniqueFilms pyramid(kWidth, kHeight, options.pyramidLength);
  SampleTargets targets;
  targets.film = &film;
  if (withPyramid) targets.pyramid = &pyramid;
  Run run;
  Pcg32 pixels(77, 5);
  for (int i = 0; i < samples; ++i) {
    const Vec2 pRaster(pixels.next1D() * kWidth, pixels.next1D() * kHeight);
    Pcg32 cameraRng(static_cast<uint64_t>(i), 1), lightRng(static_cast<uint64_t>(i), 2);
    targets.id = SampleId{static_cast<int>(pRaster.x), static_cast<int>(pRaster.y), static_cast<uint64_t>(i)};
    const Spectrum e = tracer.sample(pRaster, pixels.next2D(), cameraRng, lightRng, targets, run.counters);
    for (int c = 0; c < 3; ++c) run.estimates.push_back(std::bit_cast<uint32_t>(e[c]));
  }
  const auto sums = film.sums();
  run.splats.assign(sums[1].begin(), sums[1].end());
  return run;
}

// Which interior techniques the fast path ran: the ones whose counters it kept.
uint64_t interiorTries(const Counters& c, int maxLength) {
  uint64_t tries = 0;
  for (const Technique x : techniquesUpTo(maxLength))
    if (x.s >= 2 && x.t >= 2) tries += c.technique(x).tried;
  return tries;
}

void expectSame(const Scene& scene, const BidirOptions& options, const std::string& what, bool withPyramid = false,
                int samples = 3000) {
  const Run fast = render(scene, options, true, withPyramid, samples);
  const Run general = render(scene, options, false, withPyramid, samples);
  ASSERT_EQ(fast.estimates.size(), general.estimates.size());
  size_t differing = 0;
  for (size_t i = 0; i < fast.estimates.size(); ++i) differing += fast.estimates[i] != general.estimates[i];
  EXPECT_EQ(differing, 0u) << what << ": pixel estimates (3 a sample) that differ in a bit";
  EXPECT_TRUE(fast.splats == general.splats) << what << ": splats";
  EXPECT_EQ(fast.counters.rays, general.counters.rays) << what;
  EXPECT_EQ(fast.counters.shadowRays, general.counters.shadowRays) << what;
  for (const Technique x : techniquesUpTo(options.maxLength)) {
    const TechniqueCounters &a = fast.counters.technique(x), &b = general.counters.technique(x);
    const std::string name = what + " (" + std::to_string(x.s) + "," + std::to_string(x.t) + ")";
    EXPECT_EQ(a.tried, b.tried) << name;
    EXPECT_EQ(a.zero, b.zero) << name;
    EXPECT_EQ(a.blocked, b.blocked) << name;
    EXPECT_EQ(a.contributed, b.contributed) << name;
    EXPECT_EQ(a.shadowRays, b.shadowRays) << name;
    EXPECT_EQ(a.discarded.total(), b.discarded.total()) << name;
  }
  // The comparison means something: interior techniques were tried, and contributed.
  EXPECT_GT(interiorTries(fast.counters, options.maxLength), static_cast<uint64_t>(samples) / 10) << what;
}

Scene bundled(const std::string& name) {
  return Scene(loadGltf(std::string(PATHLAB_SOURCE_DIR) + "/assets/" + name + ".gltf"));
}

BidirOptions optionsFor(MisHeuristic h, float minConnection = 0.f, int maxLength = 8) {
  BidirOptions o;
  o.maxLength = maxLength;
  o.techniques = TechniqueSet::all();
  o.mis.heuristic = h;
  o.mis.minConnection = minConnection;
  return o;
}

TEST(InteriorFastPath, GivesTheGeneralKernelsResultsOnEveryBundledScene) {
  for (const char* name : {"cornell-box", "veach-mis", "bidir-lamp", "caustic", "many-lights", "isometric"}) {
    const Scene scene = bundled(name);
    expectSame(scene, optionsFor(MisHeuristic::Balance), name);
  }
}

TEST(InteriorFastPath, GivesTheGeneralKernelsResultsUnderEveryHeuristic) {
  const Scene scene = bundled("cornell-box");
  expectSame(scene, optionsFor(MisHeuristic::Power), "power");
  BidirOptions beta = optionsFor(MisHeuristic::Power);
  beta.mis.beta = 1.37f;
  expectSame(scene, beta, "power 1.37");
  expectSame(scene, optionsFor(MisHeuristic::Uniform, 0.f, 5), "uniform");
}

// A threshold of 30 % of the scene's radius makes many connection edges and prefixes short: those
// are weighed before their shadow ray, or declined by the sums and weighed explicitly.
TEST(InteriorFastPath, GivesTheGeneralKernelsResultsWithShortConnections) {
  expectSame(bundled("cornell-box"), optionsFor(MisHeuristic::Balance, 0.3f), "min-connection 0.3");
  expectSame(bundled("veach-mis"), optionsFor(MisHeuristic::Power, 0.3f), "veach-mis, min-connection 0.3");
}

// With a pyramid, the techniques of its lengths go through the general path and the longer ones
// through the fast path, in one sample.
TEST(InteriorFastPath, GivesTheGeneralKernelsResultsBesideAPyramid) {
  BidirOptions o = optionsFor(MisHeuristic::Balance);
  o.pyramidLength = 3;
  expectSame(bundled("cornell-box"), o, "pyramid 3", true);
}

}  // namespace
}  // namespace pathlab
