// Names of the settings' enumerations, as the CLI and the viewer print them, and the checks
// every front end runs before any work.
#include "core/render/render_settings.h"

#include "core/bpt/light_path_choice.h"

#include "core/bpt/equiangular_technique.h"

#include "core/bpt/merge_pass.h"
#include "core/bpt/mis_off.h"
#include "core/render/variance_aware_regions.h"
#include "core/bpt/path_vertex.h"
#include "core/film/technique_films.h"
#include "core/math/types.h"
#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pathlab {

namespace {

// NaN fails both comparisons, so a NaN setting is refused with the same line as one out of range.
void checkRange(const char* what, float v, float lo, float hi) {
  if (!(v >= lo && v <= hi))
    throw std::invalid_argument(fmt::format("{} {} is not a finite number in {:g}..{:g}", what, v, lo, hi));
}

void checkCamera(const CameraDesc& c) {
  for (int col = 0; col < 4; ++col)
    for (int row = 0; row < 4; ++row)
      if (!std::isfinite(c.cameraToWorld[col][row]))
        throw std::invalid_argument(fmt::format("camera transform entry {} is not finite", c.cameraToWorld[col][row]));
  if (c.orthographic && !(c.orthographic->x > 0.f && c.orthographic->y > 0.f && std::isfinite(c.orthographic->x) &&
                         std::isfinite(c.orthographic->y)))
    throw std::invalid_argument(fmt::format("orthographic camera magnification {} x {} is not positive and finite",
                                            c.orthographic->x, c.orthographic->y));
  if (!(c.yfov > 0.f && c.yfov < kPi))
    throw std::invalid_argument(fmt::format("camera field of view {} is not in (0, pi)", c.yfov));
  if (c.aspectRatio && !(*c.aspectRatio > 0.f && std::isfinite(*c.aspectRatio)))
    throw std::invalid_argument(fmt::format("camera aspect ratio {} is not a positive finite number", *c.aspectRatio));
}

}  // namespace

const char* integratorName(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::Pt: return "pt";
    case IntegratorKind::Bpt: return "bpt";
    case IntegratorKind::Lt: return "lt";
    case IntegratorKind::Mlt: return "mlt";
  }
  return "?";
}

TechniqueSet enabledTechniques(const RenderSettings& settings) {
  if (settings.integrator == IntegratorKind::Lt) return settings.techniques & TechniqueSet::lightTracing();
  return settings.techniques;
}

float mergeNonCaustic(const RenderSettings& settings) {
  if (settings.mergeNonCaustic) return *settings.mergeNonCaustic;
  const TechniqueFamilies families = enabledTechniques(settings).families();
  return covers(families, TechniqueKind::Connection) && settings.mergeSite == MergeSite::Every ? kDefaultMergeNonCaustic
                                                                                                 : 1.f;
}

float firstMergeRadius(const RenderSettings& settings) {
  if (settings.mergeRadius) return *settings.mergeRadius;
  const double pixels = std::max(1.0, static_cast<double>(settings.width) * static_cast<double>(settings.height));
  return static_cast<float>(std::min<double>(kMaxMergeRadius, kDefaultMergeRadius * std::sqrt(kDefaultMergeRadiusPixels / pixels)));
}

uint64_t mltHistogramBytes(const RenderSettings& s) {
  // Metropolis's per-length histograms (core/mlt/metropolis.h LengthTotals): 3 doubles a pixel each.
  const uint64_t lengths = s.mlt.variant == MltVariant::Multiplexed ? static_cast<uint64_t>(std::max(s.maxLength, 1)) : 1;
  return 3 * sizeof(double) * static_cast<uint64_t>(s.width) * static_cast<uint64_t>(s.height) * lengths;
}

uint64_t mergeStoreBytes(const RenderSettings& s) {
  // A stored vertex (MergePass), its path index and MIS sums, and at most as many mergeable ones:
  // the index's point, position and pointer, the grid's index, position and sort key, and the
  // merge record.
  constexpr uint64_t kPerVertex = sizeof(PathVertex) + sizeof(uint32_t) + sizeof(double) + sizeof(float) +
                                  sizeof(uint32_t) + sizeof(Vec3) + sizeof(const PathVertex*) + sizeof(uint32_t) +
                                  sizeof(Vec3) + sizeof(uint64_t) + sizeof(MergeRecord);
  return static_cast<uint64_t>(s.width) * static_cast<uint64_t>(s.height) * static_cast<uint64_t>(std::max(s.maxLength, 0)) *
         kPerVertex;
}

TechniqueFamilies sampledFamilies(const RenderSettings& settings, const Scene& scene) {
  const TechniqueFamilies f = enabledTechniques(settings).families();
  const bool equiangular = settings.integrator == IntegratorKind::Bpt &&
                           equiangularFamilySampled(scene, bidirOptions(settings));
  return equiangular ? f : without(f, TechniqueFamilies::Equiangular);
}

TechniqueFamilies pyramidFamilies(const RenderSettings& settings, const Scene& scene) {
  return TechniqueFamilies::Connections | sampledFamilies(settings, scene);
}

BidirOptions bidirOptions(const RenderSettings& s) {
  MisOptions mis = s.mis;
  mis.mediumSampling = mediumSampling(s);  // the equiangular family E(1, k) (bpt)
  return BidirOptions{s.maxLength, s.russianRoulette, enabledTechniques(s), mis,         s.isolate,   s.pyramidLength,
                      s.checkMis,  s.connect,         s.injectBias,         s.mergeSite, s.lightPaths};
}

PathTracerOptions pathTracerOptions(const RenderSettings& s) {
  return PathTracerOptions{s.maxLength, s.russianRoulette, mediumSampling(s)};
}

MediumSampling mediumSampling(const RenderSettings& settings) {
  if (settings.mediumSampling) return *settings.mediumSampling;
  if (settings.integrator == IntegratorKind::Pt) return MediumSampling::Mis;
  // bpt with path reuse and no merge: its equiangular techniques E(1, k) beside the connections
  // (not under optimal MIS, which corrects the connections' weights alone).
  const bool equiangularBpt = settings.integrator == IntegratorKind::Bpt && settings.connect == ConnectStrategy::All &&
                              settings.mis.heuristic != MisHeuristic::Optimal &&
                              !covers(enabledTechniques(settings).families(), TechniqueKind::Merge);
  return equiangularBpt ? MediumSampling::Mis : MediumSampling::Distance;
}

std::string misOffWarning(const Scene& scene, const RenderSettings& s) {
  if (s.integrator == IntegratorKind::Pt || s.mis.heuristic != MisHeuristic::Off) return "";
  const bool orthographic = s.camera.value_or(scene.cameraDesc()).orthographic.has_value();
  const bool pinhole = s.lens.apertureRadius == 0.f && !orthographic;
  const bool equiangular = s.integrator == IntegratorKind::Bpt && hasEquiangularMedium(scene);
  return misOffWarning(misOffBias(scene, enabledTechniques(s), s.maxLength, pinhole, orthographic,
                                  equiangular ? mediumSampling(s) : MediumSampling::Distance));
}

std::string mediumSamplingWarning(const Scene& scene, const RenderSettings& s) {
  if (!s.mediumSampling) return "";
  bool scatters = false;
  const std::vector<HomogeneousMedium>& media = scene.media().media();
  for (size_t i = 0; i < media.size(); ++i) {
    if (!media[i].scatters()) continue;
    scatters = true;
    if (!scene.mediumGrid(int(i))) return "";  // equiangular sampling can place vertices here
  }
  if (!scatters)
    return fmt::format("--medium-sampling {} changes nothing here: no medium in the scene scatters",
                       mediumSamplingName(*s.mediumSampling));
  // Only heterogeneous media scatter: equiangular sampling declines them (volume_grid.h).
  return fmt::format("--medium-sampling {} changes nothing here: every scattering medium is a density grid, "
                     "where only distances are sampled",
                     mediumSamplingName(*s.mediumSampling));
}

std::string optimalMisWarning(const Scene& scene, const RenderSettings& s) {
  if (s.mis.heuristic != MisHeuristic::Optimal || !scene.hasMedia()) return "";
  return "--mis optimal is not available in a scene with media: its correction needs each sample's path throughput "
         "over the true one, which distance sampling and ratio tracking leave unknown (this renders the balance "
         "heuristic)";
}

void validateSettingsForScene(const RenderSettings& s, const Scene& scene) {
  if (const std::string w = optimalMisWarning(scene, s); !w.empty())
    throw std::invalid_argument(w.substr(0, w.find(" (this renders")) + " (use --mis balance)");
}

void validateSettingsForCamera(const RenderSettings& s, const CameraDesc& sceneCamera) {
  if (!s.camera.value_or(sceneCamera).orthographic) return;
  if (s.integrator == IntegratorKind::Lt)
    throw std::invalid_argument(
        "light tracing cannot render through an orthographic camera: its rays are parallel (a delta in direction), so "
        "no light subpath can connect to it; use bpt or pt");
  if (s.lens.apertureRadius > 0.f)
    throw std::invalid_argument("an orthographic camera has no lens (its rays are parallel): set no aperture");
}

namespace {
// A heuristic's per-region tables past their budget: one line naming the option, the size and the way out.
void refuseLargeTables(const RenderSettings& s, const char* option, const char* what, uint64_t bytes, uint64_t max) {
  if (bytes <= max) return;
  throw std::invalid_argument(fmt::format(
      "{} at {} x {} with maximum length {} keeps {:.1f} GiB of {} (at most {} GiB): lower --max-length or the "
      "image size",
      option, s.width, s.height, s.maxLength, static_cast<double>(bytes) / (1ull << 30), what, max >> 30));
}
}  // namespace

void validateSettings(const RenderSettings& s) {
  if (s.width < 1 || s.height < 1)
    throw std::invalid_argument(fmt::format("image size {} x {} is not positive", s.width, s.height));
  checkRange("MIS beta", s.mis.beta, kMinBeta, kMaxBeta);
  checkRange("minimum connection", s.mis.minConnection, 0.f, kMaxMinConnection);
  checkRange("lens aperture", s.lens.apertureRadius, 0.f, kMaxAperture);
  checkRange("focus distance", s.lens.focusDistance, kMinFocusDistance, kMaxFocusDistance);
  if (s.camera) checkCamera(*s.camera);
  if (s.maxLength < 1) throw std::invalid_argument(fmt::format("maximum path length {} is less than 1", s.maxLength));
  const bool bidirectional = s.integrator != IntegratorKind::Pt;
  if (bidirectional && s.maxLength > kMaxBidirectionalLength)
    throw std::invalid_argument(fmt::format("maximum path length {} is more than the {} edges the {} integrator supports",
                                            s.maxLength, kMaxBidirectionalLength, integratorName(s.integrator)));
  if (bidirectional) s.techniques.checkFits(s.maxLength);  // throws naming the problem
  if (bidirectional && mediumSampling(s) != MediumSampling::Distance) {
    // The equiangular family E(1, k) runs in bpt with path reuse; the merges' weights and
    // Metropolis's technique choice do not count it yet.
    if (s.integrator != IntegratorKind::Bpt)
      throw std::invalid_argument(fmt::format("--medium-sampling {}: the {} integrator samples distances; equiangular "
                                              "sampling is in pt and bpt so far",
                                              mediumSamplingName(mediumSampling(s)), integratorName(s.integrator)));
    if (covers(enabledTechniques(s).families(), TechniqueKind::Merge))
      throw std::invalid_argument(fmt::format("--medium-sampling {}: the merging techniques' weights do not count the "
                                              "equiangular technique yet; use --medium-sampling distance with merges",
                                              mediumSamplingName(mediumSampling(s))));
    if (s.connect == ConnectStrategy::Endpoints)
      throw std::invalid_argument(fmt::format("--medium-sampling {}: the equiangular technique needs path reuse "
                                              "(--connect all), not naive BPT",
                                              mediumSamplingName(mediumSampling(s))));
  }
  if (bidirectional && covers(enabledTechniques(s).families(), TechniqueKind::Merge)) {
    // Vertex merging: light subpaths of the whole pass, merged at surfaces with path reuse.
    if (s.mergeRadius && !(*s.mergeRadius > 0.f && *s.mergeRadius <= kMaxMergeRadius))
      throw std::invalid_argument(fmt::format("--radius {} is outside (0, {}]", *s.mergeRadius, kMaxMergeRadius));
    if (!(s.mergeRadiusAlpha > 0.f && s.mergeRadiusAlpha <= 1.f))
      throw std::invalid_argument(fmt::format("--radius-alpha {} is outside (0, 1]", s.mergeRadiusAlpha));
    if (s.mergeNonCaustic && !(*s.mergeNonCaustic >= kMinMergeNonCaustic && *s.mergeNonCaustic <= 1.f))
      throw std::invalid_argument(
          fmt::format("--noncaustic-photons {} is outside [{}, 1]", *s.mergeNonCaustic, kMinMergeNonCaustic));
    if (s.connect == ConnectStrategy::Endpoints)
      throw std::invalid_argument("merging techniques need path reuse (--connect all), not naive BPT");
    // The merge pass stores every pixel's light subpath, up to maxLength vertices each: refused
    // before allocating when its worst case passes the budget.
    const uint64_t bytes = mergeStoreBytes(s);
    if (bytes > kMaxMergeStoreBytes)
      throw std::invalid_argument(fmt::format(
          "merging at {} x {} with maximum length {} may store {:.1f} GiB of light vertices per pass (at most {} GiB): "
          "lower --max-length or the image size",
          s.width, s.height, s.maxLength, static_cast<double>(bytes) / (1ull << 30), kMaxMergeStoreBytes >> 30));
  }
  if (s.mis.heuristic == MisHeuristic::VarianceAware) {
    if (!bidirectional)
      throw std::invalid_argument("--mis variance-aware weighs the bidirectional techniques: use bpt, lt, vcm, bpm or ppm");
    refuseLargeTables(s, "--mis variance-aware", "factors", varianceAwareBytes(s.width, s.height, s.maxLength),
                      kMaxVarianceAwareBytes);
  }
  if (s.mis.heuristic == MisHeuristic::Optimal) {
    // Optimal MIS corrects the balance weights of the connections (core/bpt/optimal_mis.h).
    if (s.integrator != IntegratorKind::Bpt)
      throw std::invalid_argument(fmt::format(
          "--mis optimal corrects the connections' balance weights: use bpt, not {}", integratorName(s.integrator)));
    if (covers(enabledTechniques(s).families(), TechniqueKind::Merge))
      throw std::invalid_argument("--mis optimal weighs connections only: merging techniques (m=...) are not among them");
    if (s.connect == ConnectStrategy::Endpoints)
      throw std::invalid_argument("--mis optimal needs path reuse (--connect all), not naive BPT");
    if (s.mediumSampling && *s.mediumSampling != MediumSampling::Distance)
      throw std::invalid_argument(fmt::format("--mis optimal weighs the connections only: use --medium-sampling "
                                              "distance, not {}",
                                              mediumSamplingName(mediumSampling(s))));
    if (s.isolate)
      throw std::invalid_argument("--isolate shows one technique unweighted: it takes no --mis optimal");
    refuseLargeTables(s, "--mis optimal", "sums", optimalMisBytes(s.width, s.height, s.maxLength), kMaxOptimalMisBytes);
  }
  if (s.lightPathsAuto) {
    const uint64_t bytes = static_cast<uint64_t>(s.width) * static_cast<uint64_t>(s.height) * kLightPathChoiceBytesPerPixel;
    if (bytes > kMaxLightPathChoiceBytes)
      throw std::invalid_argument(fmt::format("--light-paths auto at {} x {} keeps {:.1f} GiB of sums (at most {} GiB): "
                                              "lower the image size or give --light-paths a number",
                                              s.width, s.height, static_cast<double>(bytes) / (1ull << 30),
                                              kMaxLightPathChoiceBytes >> 30));
    if (s.mis.heuristic != MisHeuristic::Balance)
      throw std::invalid_argument(fmt::format("--light-paths auto estimates the balance heuristic's second moments: "
                                              "use --mis balance, not {}",
                                              misHeuristicName(s.mis.heuristic)));
  }
  if (s.lightPaths != 1.f || s.lightPathsAuto) {
    if (!(s.lightPaths >= kMinLightPaths && s.lightPaths <= 1.f))
      throw std::invalid_argument(fmt::format("--light-paths {} is outside [{}, 1]", s.lightPaths, kMinLightPaths));
    if (s.integrator != IntegratorKind::Bpt)
      throw std::invalid_argument(fmt::format("--light-paths samples light subpaths for some of a bidirectional "
                                              "tracer's camera samples: use bpt, not {}",
                                              integratorName(s.integrator)));
    if (covers(enabledTechniques(s).families(), TechniqueKind::Merge))
      throw std::invalid_argument("--light-paths: merging techniques need every pixel's light subpath (vcm, bpm, ppm "
                                  "take --light-paths 1)");
    if (s.connect == ConnectStrategy::Endpoints)
      throw std::invalid_argument("--light-paths needs path reuse (--connect all), not naive BPT");
    if (s.mis.heuristic == MisHeuristic::VarianceAware)
      throw std::invalid_argument("--light-paths is not combined with --mis variance-aware yet: take one of them");
  }
  if (s.integrator == IntegratorKind::Mlt) {
    // Metropolis over the connections: each chain state is one path of one technique (MMLT) or a
    // whole path-reuse sample (PSSMLT); what needs a sample's every technique at one pixel does not
    // apply to it.
    const MltOptions& m = s.mlt;
    if (covers(s.techniques.families(), TechniqueKind::Merge))
      throw std::invalid_argument("--integrator mlt runs over connections: merging techniques (m=...) are not among them");
    if (m.chains < 1 || m.chains > kMaxMltChains)
      throw std::invalid_argument(fmt::format("--chains {} is outside 1..{}", m.chains, kMaxMltChains));
    if (m.bootstrap < 1 || m.bootstrap > kMaxMltBootstrap)
      throw std::invalid_argument(fmt::format("--bootstrap {} is outside 1..{}", m.bootstrap, kMaxMltBootstrap));
    const uint64_t lengths = m.variant == MltVariant::Multiplexed ? static_cast<uint64_t>(std::max(s.maxLength, 1)) : 1;
    if (m.bootstrap * lengths > kMaxMltBootstrapSamples)
      throw std::invalid_argument(fmt::format("--bootstrap {} per length x {} lengths is more than {} samples to keep: "
                                              "lower --bootstrap or --max-length",
                                              m.bootstrap, lengths, kMaxMltBootstrapSamples));
    if (!(m.largeStep >= 0.f && m.largeStep <= 1.f))
      throw std::invalid_argument(fmt::format("--large-step {} is outside [0, 1]", m.largeStep));
    if (!(m.sigma >= kMinMltSigma && m.sigma <= kMaxMltSigma))
      throw std::invalid_argument(fmt::format("--sigma {} is outside [{}, {}]", m.sigma, kMinMltSigma, kMaxMltSigma));
    if (s.connect == ConnectStrategy::Endpoints)
      throw std::invalid_argument("--connect endpoints: Metropolis over naive BPT is not supported (use --connect all)");
    if (m.directLength < 0 || m.directLength > s.maxLength)
      throw std::invalid_argument(
          fmt::format("--mlt-direct {} is outside 0..{} (the maximum length)", m.directLength, s.maxLength));
    // A histogram of doubles per path length (metropolis.h): refused before allocating.
    const uint64_t bytes = mltHistogramBytes(s);
    if (bytes > kMaxMltHistogramBytes)
      throw std::invalid_argument(fmt::format(
          "mlt at {} x {} with maximum length {} keeps {:.1f} GiB of histograms (at most {} GiB): lower --max-length or "
          "the image size, or use --mlt-variant pss (one histogram)",
          s.width, s.height, s.maxLength, static_cast<double>(bytes) / (1ull << 30), kMaxMltHistogramBytes >> 30));
    const char* perSample = s.mis.heuristic == MisHeuristic::VarianceAware ? "--mis variance-aware"
                            : s.isolate                                    ? "--isolate"
                            : s.pyramidLength   ? "the technique pyramid"
                            : s.techniqueMaps   ? "the technique maps"
                            : s.varianceMaps    ? "the variance maps"
                            : s.checkTechniques ? "the consistency check"
                            : s.injectBias      ? "--inject-bias"
                                                : nullptr;
    if (perSample)
      throw std::invalid_argument(fmt::format("{} needs the bpt or lt integrator: a Metropolis chain's samples are not "
                                              "independent per pixel",
                                              perSample));
  }
  // The technique messages start with the option and its value (issue 37: both options gave the
  // same line, naming neither).
  if (s.isolate) {
    const Isolation& i = *s.isolate;
    const bool merge = i.kind == TechniqueKind::Merge;
    const std::string option =
        fmt::format("--isolate {}{},{}: ", merge ? "M" : i.kind == TechniqueKind::Equiangular ? "E" : "", i.s, i.t);
    if (!bidirectional) throw std::invalid_argument("isolating a technique needs the bpt or lt integrator");
    if (i.kind == TechniqueKind::Equiangular) {
      const Technique x = i.technique();
      if (!x.valid())
        throw std::invalid_argument(fmt::format("{}{} does not exist (an equiangular technique is E(1,t), t >= 2)",
                                                option, techniqueLabel(x)));
      if (x.length() > s.maxLength)
        throw std::invalid_argument(fmt::format("{}{} has length {}, more than the maximum length {}", option,
                                                techniqueLabel(x), x.length(), s.maxLength));
      if (s.integrator != IntegratorKind::Bpt || mediumSampling(s) == MediumSampling::Distance)
        throw std::invalid_argument(fmt::format("{}the equiangular techniques are bpt's under --medium-sampling mis or "
                                                "equiangular",
                                                option));
    } else if (merge) {
      const Technique x = i.technique();
      if (!x.valid())
        throw std::invalid_argument(fmt::format("{}merge {} does not exist (a merge needs s >= 2, t >= 2)", option,
                                                techniqueLabel(x)));
      if (x.length() > s.maxLength)
        throw std::invalid_argument(fmt::format("{}merge {} has length {}, more than the maximum length {}", option,
                                                techniqueLabel(x), x.length(), s.maxLength));
      if (s.integrator == IntegratorKind::Lt)
        throw std::invalid_argument(fmt::format("{}light tracing has only the t = 1 techniques, not {}", option,
                                                techniqueLabel(x)));
    } else {
      const int k = i.s + i.t - 1;
      if (i.s < 0 || i.t < 1 || k < 1)
        throw std::invalid_argument(
            fmt::format("{}technique ({},{}) does not exist (s >= 0, t >= 1, s + t >= 2)", option, i.s, i.t));
      if (k > s.maxLength)
        throw std::invalid_argument(fmt::format("{}technique ({},{}) has length {}, more than the maximum length {}",
                                                option, i.s, i.t, k, s.maxLength));
      if (s.integrator == IntegratorKind::Lt && i.t != 1)
        throw std::invalid_argument(
            fmt::format("{}light tracing has only the t = 1 techniques, not ({},{})", option, i.s, i.t));
    }
  }
  if (s.injectBias) {
    const BiasInjection& b = *s.injectBias;
    const Technique x = b.technique();
    const std::string option = fmt::format("--inject-bias {}{},{},{:g}: ",
                                           x.isMerge() ? "M" : x.isEquiangular() ? "E" : "", b.s, b.t, b.factor);
    if (!bidirectional) throw std::invalid_argument("injecting a bias needs the bpt or lt integrator");
    if (!x.valid())
      throw std::invalid_argument(fmt::format("{}technique {} does not exist ({})", option, techniqueLabel(x),
                                              x.isMerge() ? "a merge needs s >= 2, t >= 2" : "s >= 0, t >= 1, s + t >= 2"));
    if (x.length() > s.maxLength)
      throw std::invalid_argument(fmt::format("{}technique {} has length {}, more than the maximum length {}", option,
                                              techniqueLabel(x), x.length(), s.maxLength));
    checkRange("injected bias factor", b.factor, 0.f, kMaxInjectedBias);
  }
  if (s.checkTechniques) {
    if (!bidirectional) throw std::invalid_argument("the consistency check needs the bpt or lt integrator");
    if (s.maxLength > kMaxCheckedLength)
      throw std::invalid_argument(fmt::format("the consistency check supports paths of at most {} edges, not {}",
                                              kMaxCheckedLength, s.maxLength));
    if (s.isolate) throw std::invalid_argument("the consistency check compares the enabled techniques: not with --isolate");
    if (s.checkBlocks < 1 || s.checkBlocks > kMaxCheckBlocks)
      throw std::invalid_argument(fmt::format("check blocks {} is outside 1..{}", s.checkBlocks, kMaxCheckBlocks));
  }
  if (s.varianceMaps) {
    if (!bidirectional) throw std::invalid_argument("the variance maps need the bpt or lt integrator");
    if (s.pyramidLength == 0) throw std::invalid_argument("the variance maps need the technique pyramid (a length)");
  }
  if (s.techniqueMaps) {
    if (!bidirectional) throw std::invalid_argument("the technique maps need the bpt or lt integrator");
    if (s.pyramidLength == 0) throw std::invalid_argument("the technique maps need the technique pyramid (a length)");
  }
  if (s.pyramidLength != 0) {
    if (!bidirectional) throw std::invalid_argument("the technique pyramid needs the bpt or lt integrator");
    if (s.pyramidLength < 0 || s.pyramidLength > kMaxPyramidLength)
      throw std::invalid_argument(fmt::format("pyramid length {} is outside 1..{}", s.pyramidLength, kMaxPyramidLength));
    if (s.pyramidLength > s.maxLength)
      throw std::invalid_argument(
          fmt::format("pyramid length {} is more than the maximum path length {}", s.pyramidLength, s.maxLength));
    // The most the pyramid may keep in any scene (the equiangular family where bpt may sample it).
    TechniqueFamilies families = TechniqueFamilies::Connections | enabledTechniques(s).families();
    if (s.integrator != IntegratorKind::Bpt || mediumSampling(s) == MediumSampling::Distance)
      families = without(families, TechniqueFamilies::Equiangular);
    const uint64_t bytes =
        TechniqueFilms::bytesFor(s.width, s.height, s.pyramidLength, s.techniqueMaps, families, s.varianceMaps);
    if (bytes > kMaxPyramidBytes)
      throw std::invalid_argument(fmt::format("a pyramid of length {} at {} x {} needs {:.1f} GiB (at most {} GiB)",
                                              s.pyramidLength, s.width, s.height, static_cast<double>(bytes) / (1ull << 30),
                                              kMaxPyramidBytes >> 30));
  }
}

}  // namespace pathlab
