// BidirTracer::runImageOnly, the kernel's path for samples whose results go only to the image and
// the counters, promises what the general kernel (evaluate, run, SampleOutputs::add) gives: every
// sample's pixel estimate bit for bit, the same splats (light tracing, t = 1), and the same
// per-technique counters (tried, zero, blocked, contributed, shadow rays, discards), on every
// bundled scene, under every heuristic, with and without --min-connection (whose short
// connections it weighs before their shadow ray, as evaluate does) and beside a pyramid, whose
// techniques stay on the general path. BidirTracer::setImageOnlyPath(false) is the oracle.
#include "core/bpt/bidir_tracer.h"
#include "core/film/film.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
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
  tracer.setImageOnlyPath(fastPath);
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

// Contributions of the techniques of one kind: interior (s, t >= 2), next-event estimation (s = 1,
// t >= 2), light tracing (t = 1).
enum class Kind { Interior, NextEvent, LightTracing };
uint64_t contributions(const Counters& c, int maxLength, Kind kind) {
  uint64_t n = 0;
  for (const Technique x : techniquesUpTo(maxLength)) {
    const Kind k = x.t == 1 ? Kind::LightTracing : x.s == 1 ? Kind::NextEvent : Kind::Interior;
    if (k == kind && x.s >= 1) n += c.technique(x).contributed;
  }
  return n;
}

// Compares the two paths; returns the contributions of each kind (Kind) the comparison covered.
std::array<uint64_t, 3> expectSame(const Scene& scene, const BidirOptions& options, const std::string& what,
                                   bool withPyramid = false, int samples = 3000) {
  const Run fast = render(scene, options, true, withPyramid, samples);
  const Run general = render(scene, options, false, withPyramid, samples);
  EXPECT_EQ(fast.estimates.size(), general.estimates.size());
  size_t differing = 0;
  for (size_t i = 0; i < std::min(fast.estimates.size(), general.estimates.size()); ++i) differing += fast.estimates[i] != general.estimates[i];
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
  std::array<uint64_t, 3> covered{};
  for (const Kind kind : {Kind::Interior, Kind::NextEvent, Kind::LightTracing})
    covered[static_cast<size_t>(kind)] = contributions(fast.counters, options.maxLength, kind);
  return covered;
}

// The comparison means something: every kind of technique contributed often (some scenes have
// few of a kind: no light tracing through an orthographic camera).
void expectCovered(const std::array<uint64_t, 3>& covered, const std::string& what) {
  for (size_t kind = 0; kind < covered.size(); ++kind)
    EXPECT_GT(covered[kind], 200u) << what << ": contributions of kind " << kind << " (Kind) compared";
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

TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsOnEveryBundledScene) {
  std::array<uint64_t, 3> covered{};
  for (const char* name : {"cornell-box", "veach-mis", "bidir-lamp", "caustic", "many-lights", "isometric"}) {
    const std::array<uint64_t, 3> c = expectSame(bundled(name), optionsFor(MisHeuristic::Balance), name);
    for (size_t k = 0; k < c.size(); ++k) covered[k] += c[k];
  }
  expectCovered(covered, "bundled scenes");
}

TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsUnderEveryHeuristic) {
  const Scene scene = bundled("cornell-box");
  expectCovered(expectSame(scene, optionsFor(MisHeuristic::Power), "power"), "power");
  BidirOptions beta = optionsFor(MisHeuristic::Power);
  beta.mis.beta = 1.37f;
  expectCovered(expectSame(scene, beta, "power 1.37"), "power 1.37");
  expectCovered(expectSame(scene, optionsFor(MisHeuristic::Uniform, 0.f, 5), "uniform"), "uniform");
}

// A threshold of 30 % of the scene's radius makes many connection edges and prefixes short: those
// are weighed before their shadow ray, or declined by the sums and weighed explicitly.
TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsWithShortConnections) {
  expectCovered(expectSame(bundled("cornell-box"), optionsFor(MisHeuristic::Balance, 0.3f), "min-connection 0.3"),
                "min-connection 0.3");
  expectSame(bundled("veach-mis"), optionsFor(MisHeuristic::Power, 0.3f), "veach-mis, min-connection 0.3");
}

// With a pyramid, the techniques of its lengths go through the general path and the longer ones
// through runImageOnly, in one sample.
TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsBesideAPyramid) {
  BidirOptions o = optionsFor(MisHeuristic::Balance);
  o.pyramidLength = 3;
  expectCovered(expectSame(bundled("cornell-box"), o, "pyramid 3", true), "pyramid 3");
}

}  // namespace
}  // namespace pathlab
