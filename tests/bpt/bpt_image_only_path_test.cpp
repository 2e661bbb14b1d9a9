// The kernel's image-only route (BidirTracer::evaluate compiled without its result record, for the
// techniques whose records no output reads) promises what the recording instance gives: every
// sample's pixel estimate bit for bit, the same splats (light tracing, t = 1), and the same
// per-technique counters (tried, zero, blocked, contributed, shadow rays, discards), on every
// bundled scene, under every heuristic, with and without --min-connection (whose short
// connections it weighs before their shadow ray, as evaluate does), beside a pyramid (whose
// techniques stay on the recording instance), through a splat buffer and with timing on.
// BidirTracer::setImageOnlyPath(false) is the oracle. And the kernel's door: invalid contributions
// are dropped once, counted under their technique, before any output sees them.
#include "core/bpt/bidir_tracer.h"
#include "core/film/film.h"
#include "core/render/sample_outputs.h"
#include "core/lights/environment_file.h"
#include "core/scene/gltf_loader.h"

#include <gtest/gtest.h>

#include <array>
#include <algorithm>
#include <bit>
#include <limits>
#include <memory>

namespace pathlab {
// A named namespace: the sanitizer builds compile the tests as unity batches, where another file's
// anonymous helpers (bundled, render, ...) would collide with these.
namespace image_only_path_test {

constexpr int kWidth = 24, kHeight = 18;

// How the samples are fed: which targets, timing on or off.
struct Feed {
  bool pyramid = false;      // a pyramid of options.pyramidLength: its techniques stay on the general path
  bool splatBuffer = false;  // the t = 1 splats through a per-thread SplatBuffer, as RenderSession does
  bool timing = false;       // one sample in kTimedSampleStride timed, as --stats and the viewer do
};

struct Run {
  std::vector<uint32_t> estimates;  // 3 floats' bits per sample
  std::vector<double> splats;
  Counters counters;
};

Run render(const Scene& scene, const BidirOptions& options, bool imageOnlyPath, const Feed& feed, int samples) {
  const Camera camera(scene.cameraDesc(), kWidth, kHeight);
  BidirTracer tracer(scene, camera, options);
  tracer.setImageOnlyPath(imageOnlyPath);
  tracer.setTiming(feed.timing);
  // The comparison below means something only if one side takes the path (never with media).
  EXPECT_EQ(tracer.imageOnlyPathActive(), imageOnlyPath && !scene.hasMedia());
  Film film(kWidth, kHeight);
  SplatBuffer buffer(kWidth, kHeight);
  TechniqueFilms pyramid(kWidth, kHeight, options.pyramidLength);
  SampleTargets targets;
  targets.film = &film;
  if (feed.splatBuffer) targets.splats = &buffer;
  if (feed.pyramid) targets.pyramid = &pyramid;
  Run run;
  EXPECT_FALSE(SampleOutputs(targets).demand().records());
  Pcg32 pixels(77, 5);
  for (int i = 0; i < samples; ++i) {
    const Vec2 pRaster(pixels.next1D() * kWidth, pixels.next1D() * kHeight);
    Pcg32 cameraRng(static_cast<uint64_t>(i), 1), lightRng(static_cast<uint64_t>(i), 2);
    targets.id = SampleId{static_cast<int>(pRaster.x), static_cast<int>(pRaster.y), static_cast<uint64_t>(i)};
    SampleOutputs outputs(targets);
    tracer.sample(pRaster, pixels.next2D(), cameraRng, lightRng, outputs, run.counters);
    const Spectrum e = outputs.cameraEstimate();
    for (int c = 0; c < 3; ++c) run.estimates.push_back(std::bit_cast<uint32_t>(e[c]));
  }
  SplatSums splatSums(kWidth, kHeight);
  buffer.addTo(&splatSums, film, nullptr);
  splatSums.mergeInto(film);
  const auto sums = film.sums();
  run.splats.assign(sums[1].begin(), sums[1].end());
  return run;
}

void expectSameDiscards(const DiscardCounts& a, const DiscardCounts& b, const std::string& what) {
  EXPECT_EQ(a.nan, b.nan) << what;
  EXPECT_EQ(a.inf, b.inf) << what;
  EXPECT_EQ(a.negative, b.negative) << what;
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
                                   const Feed& feed = {}, int samples = 3000) {
  const Run fast = render(scene, options, true, feed, samples);
  const Run general = render(scene, options, false, feed, samples);
  EXPECT_EQ(fast.estimates.size(), general.estimates.size());
  size_t differing = 0;
  for (size_t i = 0; i < std::min(fast.estimates.size(), general.estimates.size()); ++i)
    differing += fast.estimates[i] != general.estimates[i];
  EXPECT_EQ(differing, 0u) << what << ": pixel estimates (3 a sample) that differ in a bit";
  EXPECT_TRUE(fast.splats == general.splats) << what << ": splats";
  EXPECT_EQ(fast.counters.rays, general.counters.rays) << what;
  EXPECT_EQ(fast.counters.shadowRays, general.counters.shadowRays) << what;
  EXPECT_EQ(fast.counters.timedSamples, general.counters.timedSamples) << what;
  for (const Technique x : techniquesUpTo(options.maxLength)) {
    const TechniqueCounters &a = fast.counters.technique(x), &b = general.counters.technique(x);
    const std::string name = what + " (" + std::to_string(x.s) + "," + std::to_string(x.t) + ")";
    EXPECT_EQ(a.tried, b.tried) << name;
    EXPECT_EQ(a.zero, b.zero) << name;
    EXPECT_EQ(a.blocked, b.blocked) << name;
    EXPECT_EQ(a.contributed, b.contributed) << name;
    EXPECT_EQ(a.shadowRays, b.shadowRays) << name;
    expectSameDiscards(a.discarded, b.discarded, name);
  }
  // Timed samples time their techniques on both paths. Summed over the techniques: a technique
  // tried once in a timed sample may read zero on either (elapsedNanoseconds gives zero when the
  // thread moves to a core whose counter lags).
  if (feed.timing) {
    uint64_t fastNs = 0, generalNs = 0;
    for (const Technique x : techniquesUpTo(options.maxLength)) {
      fastNs += fast.counters.technique(x).nanoseconds;
      generalNs += general.counters.technique(x).nanoseconds;
    }
    EXPECT_GT(fastNs, 0u) << what;
    EXPECT_GT(generalNs, 0u) << what;
  }
  EXPECT_EQ(fast.counters.discardExampleCount, general.counters.discardExampleCount) << what;
  for (size_t i = 0; i < std::min(fast.counters.discardExampleCount, general.counters.discardExampleCount); ++i) {
    const DiscardExample &a = fast.counters.discardExamples[i], &b = general.counters.discardExamples[i];
    EXPECT_TRUE(a.s == b.s && a.t == b.t && a.sample == b.sample && a.x == b.x && a.y == b.y) << what;
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

TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsOnTheBundledScenes) {
  std::array<uint64_t, 3> covered{};
  // fog: media keep every technique on the general path, and the comparison must still hold.
  for (const char* name : {"cornell-box", "veach-mis", "bidir-lamp", "caustic", "many-lights", "isometric", "fog"}) {
    const std::array<uint64_t, 3> c = expectSame(bundled(name), optionsFor(MisHeuristic::Balance), name);
    for (size_t k = 0; k < c.size(); ++k) covered[k] += c[k];
  }
  // The sky map: paths escaping to the environment (s = 0), next-event estimation and shadow rays
  // toward infinity.
  const std::string source = PATHLAB_SOURCE_DIR;
  LoadOptions load;
  load.environment = std::make_shared<EnvironmentDesc>(readEnvironment(source + "/assets/sky.hdr"));
  const std::array<uint64_t, 3> c =
      expectSame(Scene(loadGltf(source + "/assets/environment.gltf", load)), optionsFor(MisHeuristic::Balance), "environment");
  for (size_t k = 0; k < c.size(); ++k) covered[k] += c[k];
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
// through the image-only route, in one sample; the render sessions' splat buffer; timing on (the timed
// samples take the image-only path too, and time the same work).
TEST(ImageOnlyPath, GivesTheGeneralKernelsResultsWithEveryFeed) {
  BidirOptions o = optionsFor(MisHeuristic::Balance);
  o.pyramidLength = 3;
  expectCovered(expectSame(bundled("cornell-box"), o, "pyramid 3", Feed{.pyramid = true}), "pyramid 3");
  const BidirOptions plain = optionsFor(MisHeuristic::Balance);
  expectCovered(expectSame(bundled("cornell-box"), plain, "splat buffer", Feed{.splatBuffer = true}), "splat buffer");
  expectCovered(expectSame(bundled("cornell-box"), plain, "timing", Feed{.timing = true}), "timing");
}

// Invalid contributions (NaN, Inf, negative) are dropped at the kernel's door, once, counted by
// kind under their technique and kept as examples with their sample, and never reach an output:
// a technique made invalid by an injected factor (BiasInjection) leaves the splats and the other
// techniques' estimates finite, on the recording instance and (with no injection, checked above
// to match it) the image-only one alike.
TEST(ImageOnlyPath, TheKernelsDoorDropsInvalidContributions) {
  const Scene scene = bundled("cornell-box");
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  struct Case {
    Technique x;
    float factor;
    uint64_t DiscardCounts::*kind;
  };
  for (const Case& c : {Case{{1, 2}, -1.f, &DiscardCounts::negative}, Case{{2, 1}, nan, &DiscardCounts::nan},
                        Case{{2, 2}, inf, &DiscardCounts::inf}}) {
    BidirOptions o = optionsFor(MisHeuristic::Balance);
    o.injectBias = BiasInjection{c.x.s, c.x.t, c.factor};
    const Camera camera(scene.cameraDesc(), kWidth, kHeight);
    const BidirTracer tracer(scene, camera, o);
    Film film(kWidth, kHeight);
    SampleTargets targets;
    targets.film = &film;
    Counters counters;
    Pcg32 pixels(77, 5);
    bool finite = true;
    for (int i = 0; i < 2000; ++i) {
      const Vec2 pRaster(pixels.next1D() * kWidth, pixels.next1D() * kHeight);
      Pcg32 cameraRng(static_cast<uint64_t>(i), 1), lightRng(static_cast<uint64_t>(i), 2);
      targets.id = SampleId{static_cast<int>(pRaster.x), static_cast<int>(pRaster.y), static_cast<uint64_t>(i)};
      SampleOutputs outputs(targets);
      tracer.sample(pRaster, pixels.next2D(), cameraRng, lightRng, outputs, counters);
      finite = finite && isValidContribution(outputs.cameraEstimate());
    }
    const std::string name = std::to_string(c.x.s) + "," + std::to_string(c.x.t);
    EXPECT_TRUE(finite) << name << ": an invalid contribution reached a pixel estimate";
    const auto sums = film.sums();  // the array of spans outlives the loop (a temporary would not)
    for (const double v : sums[1]) ASSERT_TRUE(std::isfinite(v) && v >= 0.0) << name << ": a splat";
    const TechniqueCounters& tc = counters.technique(c.x);
    EXPECT_GT(tc.contributed, 50u) << name;
    // By its reason (an Inf factor times a zero channel is a NaN: isValidContribution's order).
    EXPECT_GT(tc.discarded.*c.kind, tc.contributed / 2) << name;
    EXPECT_EQ(tc.discarded.total(), tc.contributed) << name;
    EXPECT_EQ(counters.discarded(), tc.contributed) << name << ": only the injected technique's";
    ASSERT_EQ(counters.discardExampleCount, kDiscardExamples) << name;
    for (size_t i = 0; i < counters.discardExampleCount; ++i) {
      const DiscardExample& e = counters.discardExamples[i];
      EXPECT_TRUE(e.s == c.x.s && e.t == c.x.t) << name;
      EXPECT_TRUE(e.x >= 0 && e.x < kWidth && e.y >= 0 && e.y < kHeight) << name << ": the sample's pixel";
    }
  }
}

}  // namespace image_only_path_test
}  // namespace pathlab
