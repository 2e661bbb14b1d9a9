// Everything that changes the estimate. The viewer edits a copy; a difference from the active
// settings (defaulted operator==) starts a new generation of the film.
#pragma once

#include "core/bpt/bidir_options.h"
#include "core/bpt/mis_options.h"
#include "core/bpt/technique_set.h"
#include "core/media/medium_sampling.h"
#include "core/mlt/mlt_options.h"
#include "core/pt/path_tracer.h"
#include "core/camera/camera.h"
#include "core/scene/scene_desc.h"

#include <cstdint>
#include <optional>
#include <string>

namespace pathlab {

class Scene;

// Pt: the path tracer; Bpt: bidirectional; Lt: bidirectional restricted to t = 1 (light tracing);
// Mlt: Metropolis light transport over the bidirectional techniques (core/mlt/metropolis.h).
enum class IntegratorKind { Pt, Bpt, Lt, Mlt };

struct RenderSettings {
  int width = 512;
  int height = 512;
  int maxLength = 10;            // maximum path length in edges (a visible emitter is 1)
  bool russianRoulette = true;   // core/sampling/russian_roulette.h
  uint64_t seed = 0;
  IntegratorKind integrator = IntegratorKind::Pt;
  LensOptions lens;
  std::optional<CameraDesc> camera;  // overrides the scene's camera (the viewer's orbit/fly)
  TechniqueSet techniques = TechniqueSet::all();  // Bpt and Lt only; see enabledTechniques
  MisOptions mis;
  ConnectStrategy connect = ConnectStrategy::All;  // Bpt and Lt only: path reuse or naive BPT
  std::optional<Isolation> isolate;  // Bpt and Lt only
  // > 0: also accumulate every technique (s, t) of length <= pyramidLength, weighted and
  // unweighted, in films of their own (the technique pyramid, Veach 1997 fig. 10.3).
  int pyramidLength = 0;
  // With pyramidLength > 0: the pyramid also keeps, per technique, the part of its length's image
  // it can sample at all, for the technique maps' "cannot sample" (core/film/technique_maps.h).
  bool techniqueMaps = false;
  // With pyramidLength > 0: the pyramid also keeps, per technique, the second moment of its
  // estimate across passes, for the variance maps (TechniqueFilms::readoutVariance).
  bool varianceMaps = false;
  // Bpt and Lt only: one technique made wrong on purpose (BiasInjection); the image is biased.
  std::optional<BiasInjection> injectBias;
  // Bpt and Lt only: accumulate the consistency check of every enabled technique against the
  // others on the paths both can sample (core/check/technique_check.h).
  bool checkTechniques = false;
  int checkBlocks = 4;  // the check's regions: a checkBlocks x checkBlocks grid and the whole image
  // Vertex merging (the techniques' merges): the first pass's radius as a fraction of the scene's
  // bounding radius (unset: firstMergeRadius() picks it from the image size), and alpha of the
  // progressive schedule r_i = r_1 i^((alpha - 1) / 2) (core/bpt/merge_pass.h; SmallVCM's 0.75).
  std::optional<float> mergeRadius;
  float mergeRadiusAlpha = 0.75f;
  // The share of the non-caustic light vertices (not reached by a delta bounce) a pass keeps for
  // merging, each kept one standing for 1 / share of them; caustic ones are always kept
  // (MergePass::index, mergeKeep). One: every vertex, Georgiev et al.'s VCM. Unset: mergeNonCaustic().
  std::optional<float> mergeNonCaustic;
  // Media: how the path tracer places the medium vertex of its connection to a light
  // (core/media/medium_sampling.h). Unset: mediumSampling().
  std::optional<MediumSampling> mediumSampling;
  // Progressive photon mapping (Hachisuka, Ogaki and Jensen 2008) among the merges: a camera
  // subpath merges only at its first vertex that is not a delta scatter (MergeSite).
  MergeSite mergeSite = MergeSite::Every;
  // Bpt only: light subpaths per pass as a fraction of its camera samples, (0, 1] (efficiency-aware
  // sampling, Grittmann et al. 2022). Each camera sample walks a light subpath with this
  // probability; the techniques that need one (t = 1, and s >= 2) then count this many samples in
  // every MIS weight and their contributions are divided by it (core/bpt/light_paths.h).
  float lightPaths = 1.f;
  // --light-paths auto: lightPaths chosen per image from the passes' own second moments and ray
  // counts (core/bpt/light_path_choice.h); lightPaths is then the F of the passes before the first
  // choice (1 from the command line).
  bool lightPathsAuto = false;
  // Mlt only: the chains (core/mlt/mlt_options.h). A pass is one mutation per pixel on average.
  MltOptions mlt;
  // Check on every path that the MIS weights of the enabled techniques able to produce it sum to
  // one (Counters::misPartitionFailures). On by default in debug builds.
#ifdef NDEBUG
  bool checkMis = false;
#else
  bool checkMis = true;
#endif

  bool operator==(const RenderSettings&) const = default;
};

// Whether a and b render the same view with the same estimator, at possibly different resolutions
// (the viewer's image follows its area of the window: a panel that opens resizes it).
inline bool sameExceptSize(RenderSettings a, const RenderSettings& b) {
  a.width = b.width;
  a.height = b.height;
  return a == b;
}

inline constexpr int kMaxPyramidLength = 8;
// The fewest light subpaths per camera sample (--light-paths): below, a technique's contributions
// would be divided by more than a thousand.
inline constexpr float kMinLightPaths = 0.001f;
inline constexpr float kMaxMergeRadius = 0.5f;  // of the scene's bounding radius
// The default first radius at 512 x 512 pixels (SmallVCM's radius at its default image size),
// scaled by 512 / sqrt(width x height) elsewhere: see firstMergeRadius.
inline constexpr float kDefaultMergeRadius = 0.003f;
inline constexpr float kDefaultMergeRadiusPixels = 512.f * 512.f;
// Below this a kept non-caustic vertex would carry more than a thousand times its throughput.
inline constexpr float kMinMergeNonCaustic = 0.001f;
// The share where the set has connections beside merges at every camera vertex (vcm): there the
// connections carry what the non-caustic merges would, and keeping a twentieth of those vertices
// took the all-diffuse box from 0.47 to about 0.7 of BPT's efficiency, and the mirror-and-glass
// box's caustic region from 1.9x to 2.2x BPT's (docs/benchmarks.md, "Session 20: non-caustic
// photons"). Without connections (bpm) or with one merge per path (ppm) the merges are all
// there is: every vertex is kept.
inline constexpr float kDefaultMergeNonCaustic = 0.05f;
inline constexpr uint64_t kMaxMergeStoreBytes = 8ull << 30;
// The consistency check keeps a mask of the techniques able to sample each path (one bit each).
inline constexpr int kMaxCheckedLength = 30;
inline constexpr float kMaxInjectedBias = 1e6f;
inline constexpr int kMaxCheckBlocks = 16;
// The bidirectional tracers connect O(n^2) prefix pairs with O(n) weights each and their technique
// tables hold about n^2 / 2 entries: beyond this many edges that is memory and time for nothing.
inline constexpr int kMaxBidirectionalLength = kMaxTechniqueLength;
inline constexpr uint64_t kMaxPyramidBytes = 8ull << 30;
// Ranges of the float settings, shared by the CLI's checks and validateSettings.
inline constexpr float kMinBeta = 0.01f, kMaxBeta = 100.f;
inline constexpr float kMaxMinConnection = 1.f;
inline constexpr float kMaxAperture = 1e6f;
inline constexpr float kMinFocusDistance = 1e-6f, kMaxFocusDistance = 1e9f;

const char* integratorName(IntegratorKind kind);

// The techniques the bidirectional tracer weighs and adds to the image: settings.techniques, less
// every t >= 2 under `lt` (light tracing, TechniqueSet::lightTracing). The path tracer ignores them.
TechniqueSet enabledTechniques(const RenderSettings& settings);
// The share of non-caustic light vertices a merge pass keeps: settings.mergeNonCaustic when set,
// else kDefaultMergeNonCaustic where connections are enabled beside merges at every camera vertex,
// one otherwise.
float mergeNonCaustic(const RenderSettings& settings);
// The first pass's merge radius, a fraction of the scene's bounding radius: settings.mergeRadius
// when set, else kDefaultMergeRadius x sqrt(512^2 / pixels), at most kMaxMergeRadius. A pass has
// one light subpath per pixel, so a disk of radius r holds on average (light vertex density per
// subpath) x pi r^2 x pixels of them: r proportional to 1 / sqrt(pixels) keeps that count, and the
// disk's size against a pixel, the same at every image size. The merges' variance and blur then
// look alike at any resolution; at a fixed radius a 256^2 image merged a quarter as many vertices
// per disk as a 512^2 one (measured: docs/benchmarks.md, "Session 21").
float firstMergeRadius(const RenderSettings& settings);
// settings.mediumSampling when set, else MIS of distance and equiangular sampling: the path
// tracer's, and bpt's with path reuse and no merge (its equiangular techniques E(1, k) beside the
// connections); distance sampling for lt, mlt, merges and naive BPT (validateSettings refuses the
// others there).
MediumSampling mediumSampling(const RenderSettings& settings);
// The families the technique pyramid keeps: every connection up to its length, the merges when any
// is enabled, the equiangular techniques E(1, k) when bpt samples them in this scene
// (equiangularFamilySampled): a family no technique uses costs no memory and shows no tile.
TechniqueFamilies pyramidFamilies(const RenderSettings& settings, const Scene& scene);
// The families of settings.techniques the tracer samples in this scene: enabledTechniques' less
// the equiangular family where it is not sampled. What the tables, grids and maps cover.
TechniqueFamilies sampledFamilies(const RenderSettings& settings, const Scene& scene);
// The most a pass's merge store (core/bpt/merge_pass.h) can take: every pixel's light subpath at
// the maximum length.
uint64_t mergeStoreBytes(const RenderSettings& settings);
// The most Metropolis's histograms take: 3 doubles a pixel for each path length (PSSMLT: one).
uint64_t mltHistogramBytes(const RenderSettings& settings);
inline constexpr uint64_t kMaxMltHistogramBytes = 8ull << 30;
// Variance-aware MIS: the factors' tables (VarianceAwareFactors::bytesFor) at most this much.
inline constexpr uint64_t kMaxVarianceAwareBytes = 2ull << 30;
// --mis optimal: its regions' sums (OptimalMis::bytesFor) at most this much.
inline constexpr uint64_t kMaxOptimalMisBytes = 2ull << 30;
// --light-paths auto: its per-pixel sums (kLightPathChoiceBytesPerPixel) at most this much.
inline constexpr uint64_t kMaxLightPathChoiceBytes = uint64_t{1} << 30;
// What each tracer needs of the settings.
BidirOptions bidirOptions(const RenderSettings& settings);
PathTracerOptions pathTracerOptions(const RenderSettings& settings);

// The one-line warning of MIS off (mis_off.h) for these settings in this scene: which lengths are
// biased and why; "" for any other heuristic, the path tracer, or an unbiased scene.
std::string misOffWarning(const Scene& scene, const RenderSettings& settings);
// When --medium-sampling is given for a scene in which no medium scatters, or in which only
// density grids do (equiangular sampling declines them): it changes nothing there, and a user
// comparing the modes should know. Empty otherwise.
std::string mediumSamplingWarning(const Scene& scene, const RenderSettings& settings);

// Throws std::invalid_argument with a one-line message naming the setting when the settings
// cannot be rendered: no technique of length 1..maxLength enabled or one listed beyond it, an
// isolated technique outside 1..maxLength or not a light-tracing one under `lt`, isolation or a
// pyramid (or technique maps without one) asked of the path tracer, a pyramid longer than maxLength or kMaxPyramidLength or too
// large for memory; a float setting that is not finite or outside its range (MIS beta and minimum
// connection, lens aperture and focus distance, an override camera's transform and field of view),
// whichever route it came by (CLI, converge configurations, viewer presets).
void validateSettings(const RenderSettings& settings);
// What the camera the settings render through refuses (their override, else the scene's camera):
// an orthographic camera has no lens and no light subpath can connect to it, so it refuses an
// aperture and the light tracer. Throws std::invalid_argument naming the problem.
void validateSettingsForCamera(const RenderSettings& settings, const CameraDesc& sceneCamera);
// The refusals that depend on the scene's content: throws std::invalid_argument naming the
// problem. --mis optimal in a scene with media (its correction needs each sample's estimated path
// throughput over the true one, which the walks' distance sampling and ratio tracking leave
// stochastic and unknown; core/bpt/optimal_mis.h). The commands call it before rendering; a
// RenderSession given such settings renders the balance heuristic (no correction), which the
// viewer's status reports (optimalMisWarning: the same text, or "").
void validateSettingsForScene(const RenderSettings& settings, const Scene& scene);
std::string optimalMisWarning(const Scene& scene, const RenderSettings& settings);

}  // namespace pathlab
