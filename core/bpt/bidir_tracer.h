// The bidirectional path tracer's per-sample kernel: both subpaths, every enabled (s, t),
// weighted by misWeight; light-tracing (t = 1) contributions are splatted to the film.
#pragma once

#include "core/bpt/mis.h"
#include "core/bpt/subpath.h"
#include "core/bpt/technique_set.h"
#include "core/film/film.h"
#include "core/film/technique_films.h"
#include "core/render/render_settings.h"

#include <optional>

namespace pathlab {

// pbrt-v4 issue 347: the number of light subpaths per pass sets both the t = 1 splat scale
// (Film::finishPass) and the t = 1 sample count in the MIS weight. One light subpath is traced
// per camera sample; this is the only place that says so.
inline constexpr uint64_t kLightSubpathsPerCameraSample = 1;
inline uint64_t lightSubpathsPerPass(uint64_t pixelCount) { return pixelCount * kLightSubpathsPerCameraSample; }
inline float lightTracingRatio() { return static_cast<float>(kLightSubpathsPerCameraSample); }

// One technique's part of a replayed sample (`pathlab render --replay`).
struct TechniqueRecord {
  int s = 0, t = 1;
  Spectrum unweighted{0.f};  // connect(s, t)'s contribution
  float weight = 0.f;        // its MIS weight among the enabled techniques (0 if disabled)
  Vec2 pRaster{0.f};         // where it lands: the sample's own pixel, or the splat position (t = 1)
  bool blocked = false;
  bool inImage = false;      // reached the image (enabled, or the isolated technique)
};
struct SampleTrace {
  int cameraVertices = 0, lightVertices = 0;
  std::vector<TechniqueRecord> records;  // every technique tried, in evaluation order
};

// Which sample this is, for the discarded-sample report (Counters::discardExamples).
struct SampleId {
  int x = -1, y = -1;
  uint64_t sample = 0;
};

// Where one sample's contributions go: the t = 1 splats of the image to `film`, every technique
// of the pyramid's lengths, weighted and unweighted, to `pyramid`, and a record of each
// technique to `trace`. Each may be null.
struct SampleTargets {
  Film* film = nullptr;
  TechniqueFilms* pyramid = nullptr;
  SampleTrace* trace = nullptr;
  SampleId id;
};

class BidirTracer {
 public:
  BidirTracer(const Scene& scene, const Camera& camera, const RenderSettings& settings);

  // One camera sample through pRaster and one light subpath: returns the camera-side pixel
  // estimate (t >= 2) and splats the t = 1 contributions. Contributions that are NaN, Inf or
  // negative are dropped one technique at a time and counted under that technique.
  Spectrum sample(Vec2 pRaster, Vec2 uLens, Pcg32& cameraRng, Pcg32& lightRng, const SampleTargets& targets,
                  Counters& counters) const;

  const TechniqueSet& techniques() const { return techniques_; }

  // Time the walks and every technique's connect() + misWeight into the counters, on one camera
  // sample in eight (Counters::timedSamples counts them). Off by default: when off it costs one
  // branch. Not a RenderSettings member, so switching it never starts a new generation; set it
  // between passes, never during one.
  void setTiming(bool on) { timing_ = on; }
  bool timing() const { return timing_; }

 private:
  const Scene& scene_;
  const Camera& camera_;
  int maxLength_;
  bool russianRoulette_;
  TechniqueSet techniques_;  // the enabled set: MIS weights are normalised over it
  MisOptions mis_;
  std::optional<Isolation> isolate_;
  int pyramidLength_;
  bool checkMis_;
  int cameraVerticesNeeded_ = 1;  // the camera vertex itself is always there
  int lightVerticesNeeded_ = 0;
  bool timing_ = false;
};

}  // namespace pathlab
