// Registration and post-processing of the estimator options.
#include "app/estimator_options.h"

#include "core/sampling/technique_label.h"

#include <fmt/core.h>

#include <charconv>
#include <cstdlib>
#include <map>
#include <stdexcept>

namespace pathlab::app {

namespace {

int parseInt(const std::string& text, const std::string& what) {
  int v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc() || ptr != end) throw std::invalid_argument(fmt::format("{}: '{}' is not an integer", what, text));
  return v;
}

}  // namespace

void addEstimatorOptions(CLI::App* cmd, EstimatorOptions& o) {
  RenderSettings& s = o.settings;
  cmd->add_option("--max-length", s.maxLength,
                  "Maximum path length in edges (1: emitters seen directly, 2: direct lighting)")
      ->check(CLI::Range(1, 100000));
  cmd->add_option("--integrator", o.integrator,
                  "Estimator: bpt (bidirectional, default), pt (path tracer), lt (light tracing: the t = 1 techniques), "
                  "vcm (bpt with every merge: vertex connection and merging), bpm (the merges alone: bidirectional "
                  "photon mapping), ppm (progressive photon mapping: merges at the first non-specular camera vertex, "
                  "and camera paths that hit a light), mlt (Metropolis light transport over the bidirectional "
                  "techniques: multiplexed by default, --mlt-variant)")
      ->transform(CLI::IsMember({"pt", "bpt", "lt", "vcm", "bpm", "ppm", "mlt"}, CLI::ignore_case));
  cmd->add_option("--mlt-variant", o.mltVariant,
                  "mlt: mmlt (multiplexed MLT, Hachisuka et al. 2014: each chain keeps one path length, its state also picking "
                  "the technique) or pss (primary sample space MLT, Kelemen et al. 2002, over whole bidirectional samples)")
      ->transform(CLI::IsMember({"mmlt", "pss"}, CLI::ignore_case));
  cmd->add_option("--chains", o.chains, "mlt: the number of Markov chains (default 1000)")
      ->check(CLI::Range(1, kMaxMltChains));
  cmd->add_option("--bootstrap", o.bootstrap,
                  "mlt: independent samples per path length (pss: in all) that estimate the normalisation and start "
                  "the chains (default 100000)")
      ->check(CLI::Range(uint64_t{1}, kMaxMltBootstrap));
  cmd->add_option("--large-step", o.largeStep, "mlt: the probability of a large step, an independent sample (default 0.3)")
      ->check(CLI::Range(0.f, 1.f));
  cmd->add_option("--sigma", o.sigma,
                  "mlt: the small step's standard deviation in primary sample space (default 0.01)")
      ->check(CLI::Range(kMinMltSigma, kMaxMltSigma));
  cmd->add_option("--mlt-direct", o.mltDirect,
                  "mlt: paths of up to K edges (1: lights seen directly, 2: direct lighting) rendered by BPT beside "
                  "the chains, one sample a pixel a pass; the chains explore the longer ones (default 0: the chains "
                  "render every length)")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--mis", s.mis.heuristic,
                  "MIS heuristic of bpt: balance, power, uniform, off (1/n_k per technique of length k: biased "
                  "with delta lights or BSDFs), or variance-aware (balance with each technique's count scaled by "
                  "its second moment over its variance, estimated per region from the earlier passes; Grittmann et "
                  "al. 2019), or optimal (the balance weights corrected to the weights of least variance, "
                  "coefficients per region and length from the earlier passes; Kondapaneni et al. 2019)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, MisHeuristic>{{"balance", MisHeuristic::Balance},
                                              {"power", MisHeuristic::Power},
                                              {"uniform", MisHeuristic::Uniform},
                                              {"off", MisHeuristic::Off},
                                              {"variance-aware", MisHeuristic::VarianceAware},
                                              {"optimal", MisHeuristic::Optimal}},
          CLI::ignore_case));
  cmd->add_option("--connect", s.connect,
                  "Subpaths of bpt: all (one pair per sample, every prefix pair connected) or endpoints (naive BPT: "
                  "subpaths of their own per technique, endpoints connected)")
      ->transform(CLI::CheckedTransformer(
          std::map<std::string, ConnectStrategy>{{"all", ConnectStrategy::All}, {"endpoints", ConnectStrategy::Endpoints}},
          CLI::ignore_case));
  cmd->add_option("--beta", s.mis.beta, "Exponent of the power heuristic")->check(CLI::Range(kMinBeta, kMaxBeta));
  cmd->add_option("--min-connection", s.mis.minConnection,
                  "Connections shorter than this fraction of the scene's bounding radius are left to the techniques "
                  "that sample that edge, when one is enabled (0: off)")
      ->check(CLI::Range(0.f, kMaxMinConnection));
  cmd->add_option_function<std::string>(
         "--light-paths",
         [&s](const std::string& value) {
           if (value == "auto") {
             s.lightPathsAuto = true, s.lightPaths = 1.f;
             return;
           }
           float f = 0.f;
           size_t used = 0;
           try {
             f = std::stof(value, &used);
           } catch (const std::exception&) {
             used = 0;
           }
           if (used != value.size() || !(f >= kMinLightPaths && f <= 1.f))
             throw CLI::ValidationError("--light-paths",
                                        fmt::format("'{}' is neither auto nor a number in [{}, 1]", value, kMinLightPaths));
           s.lightPathsAuto = false, s.lightPaths = f;
         },
         "bpt: light subpaths per pass as a fraction of the camera samples, or auto (each camera sample walks one "
         "with this probability; light tracing and the connections beyond next-event estimation count it in every MIS "
         "weight; auto chooses it per image from the passes' second moments and ray counts, Grittmann et al. 2022)")
      ->type_name("auto|F");
  cmd->add_option("--techniques", o.techniques,
                  "Enabled techniques of bpt: ';'-separated S,T | s=S | t=T | k=K | all (connections and the equiangular "
                  "E(1,t) in fog), E1,T, MS,T | m=K | m=all (merges; 'all;m=all' is vertex connection and merging)");
  cmd->add_option("--radius", s.mergeRadius,
                  "Merging radius of the first pass, a fraction of the scene's bounding radius (default: 0.003 at 512 x 512 "
                  "pixels, times 512 / sqrt(width x height) at other sizes)")
      ->check(CLI::Range(0.f, kMaxMergeRadius));
  cmd->add_option("--radius-alpha", s.mergeRadiusAlpha,
                  "Progressive radius: pass i merges within r_1 i^((alpha - 1) / 2) (1: fixed radius)")
      ->check(CLI::Range(0.f, 1.f));
  cmd->add_option("--noncaustic-photons", s.mergeNonCaustic,
                  "Share of the light vertices not reached through a mirror or glass that a pass keeps for merging, "
                  "each standing for 1/share of them (caustic ones are always kept; 1: every vertex, VCM as published)")
      ->check(CLI::Range(kMinMergeNonCaustic, 1.f));
  cmd->add_option_function<std::string>(
         "--medium-sampling",
         [&s](const std::string& name) {
           const std::optional<MediumSampling> m = parseMediumSampling(name);
           if (!m) throw CLI::ValidationError("--medium-sampling", "'" + name + "' is not distance, equiangular or mis");
           s.mediumSampling = m;
         },
         "In media, how the scattering vertex that connects to a light is placed: distance (along the "
         "transmittance), equiangular (toward the light point, Kulla and Fajardo 2012) or mis (both; the default of pt "
         "and bpt). bpt: its equiangular techniques E(1,k) beside the connections (mis) or in place of C(1,k) "
         "(equiangular), or left out (distance); lt, mlt, merges and naive BPT sample distances")
      ->type_name("distance|equiangular|mis");
  auto* isolate = cmd->add_option("--isolate", o.isolate,
                                  "Show technique S,T (or merge MS,T, equiangular E1,T) alone: its MIS-weighted share (or with --unweighted its own estimate)");
  cmd->add_flag("--unweighted", o.unweighted,
                "With --isolate: the technique's unweighted estimate of every path of its length it can sample")
      ->needs(isolate);
  cmd->add_option("--inject-bias", o.injectBias,
                  "S,T,FACTOR: multiply technique (S,T)'s unweighted contribution by FACTOR, a deliberate bug that "
                  "biases the image (for teaching and for `pathlab check`); MS,T,FACTOR: the merge M(S,T)");
  // A callback, not a negated flag: CLI11 prints a negated flag as "--no-rr{false}".
  cmd->add_flag_callback("--no-rr", [&s] { s.russianRoulette = false; },
                         "Turn Russian roulette off (it is on by default, from the second scattering on; delta bounces always continue)");
  cmd->add_option("--seed", s.seed, "Seed of every random stream (samples are keyed by seed, pixel, index)");
  cmd->add_option("--aperture", s.lens.apertureRadius, "Thin-lens aperture radius in scene units (0: pinhole)")
      ->check(CLI::Range(0.f, kMaxAperture));
  cmd->add_option("--focus-distance", s.lens.focusDistance, "Thin-lens focus distance in scene units")
      ->check(CLI::Range(kMinFocusDistance, kMaxFocusDistance));
}

void finishEstimatorOptions(EstimatorOptions& o) {
  // vcm and bpm are bpt with a technique set of their own.
  static const std::map<std::string, std::pair<IntegratorKind, const char*>> kIntegrators = {
      {"pt", {IntegratorKind::Pt, "all"}},
      {"bpt", {IntegratorKind::Bpt, "all"}},
      {"lt", {IntegratorKind::Lt, "all"}},
      {"vcm", {IntegratorKind::Bpt, "all;m=all"}},
      {"bpm", {IntegratorKind::Bpt, "m=all"}},
      {"ppm", {IntegratorKind::Bpt, "s=0;m=all"}},
      {"mlt", {IntegratorKind::Mlt, "all"}}};
  const auto integrator = kIntegrators.find(o.integrator);
  if (integrator == kIntegrators.end()) throw std::invalid_argument(fmt::format("--integrator: '{}' is unknown", o.integrator));
  const auto [kind, ownTechniques] = integrator->second;
  const bool setsTechniques = o.integrator == "vcm" || o.integrator == "bpm" || o.integrator == "ppm";
  if (setsTechniques && !o.techniques.empty())
    throw std::invalid_argument(fmt::format("--integrator {} sets the techniques ({}): for another set use --integrator "
                                            "bpt --techniques",
                                            o.integrator, ownTechniques));
  o.settings.integrator = kind;
  const char* mltOption = o.mltVariant ? "--mlt-variant"
                          : o.chains   ? "--chains"
                          : o.bootstrap ? "--bootstrap"
                          : o.largeStep ? "--large-step"
                          : o.sigma     ? "--sigma"
                          : o.mltDirect ? "--mlt-direct"
                                        : nullptr;
  if (mltOption && kind != IntegratorKind::Mlt)
    throw std::invalid_argument(fmt::format("{} applies to --integrator mlt, not {}", mltOption, o.integrator));
  MltOptions& mlt = o.settings.mlt;
  if (o.mltVariant) mlt.variant = *parseMltVariant(*o.mltVariant);
  if (o.chains) mlt.chains = *o.chains;
  if (o.bootstrap) mlt.bootstrap = *o.bootstrap;
  if (o.largeStep) mlt.largeStep = *o.largeStep;
  if (o.sigma) mlt.sigma = *o.sigma;
  if (o.mltDirect) mlt.directLength = *o.mltDirect;
  // ppm: the merges at each camera subpath's first non-specular vertex, and the camera subpaths
  // that hit a light (what no merge samples: lights seen directly or in mirrors and glass).
  o.settings.mergeSite = o.integrator == "ppm" ? MergeSite::FirstNonSpecular : MergeSite::Every;
  o.settings.techniques = TechniqueSet::parse(o.techniques.empty() ? ownTechniques : o.techniques);
  if (!o.isolate.empty()) {
    try {
      o.settings.isolate = parseIsolation(o.isolate);  // "M2,3": the merge M(2,3)
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--isolate: ") + e.what());
    }
    o.settings.isolate->unweighted = o.unweighted;
  }
  if (!o.injectBias.empty()) {
    const size_t a = o.injectBias.find(','), b = a == std::string::npos ? a : o.injectBias.find(',', a + 1);
    if (b == std::string::npos) throw std::invalid_argument(fmt::format("--inject-bias: '{}' is not S,T,FACTOR", o.injectBias));
    const std::string factorText = o.injectBias.substr(b + 1);
    char* end = nullptr;
    const double factor = std::strtod(factorText.c_str(), &end);
    if (factorText.empty() || end != factorText.c_str() + factorText.size())
      throw std::invalid_argument(fmt::format("--inject-bias: '{}' is not a number", factorText));
    if (!(factor >= 0.0 && factor <= kMaxInjectedBias))
      throw std::invalid_argument(fmt::format("--inject-bias: factor {} is outside 0..{:g}", factorText, kMaxInjectedBias));
    // "M2,2,2": the merge M(2,2) (its normalisation doubled, say); "E1,2,1.1": the equiangular E(1,2).
    const bool merge = o.injectBias[0] == 'M' || o.injectBias[0] == 'm';
    const bool equiangular = o.injectBias[0] == 'E' || o.injectBias[0] == 'e';
    const size_t from = merge || equiangular ? 1 : 0;
    o.settings.injectBias = BiasInjection{parseInt(o.injectBias.substr(from, a - from), "--inject-bias"),
                                          parseInt(o.injectBias.substr(a + 1, b - a - 1), "--inject-bias"),
                                          static_cast<float>(factor),
                                          merge         ? TechniqueKind::Merge
                                          : equiangular ? TechniqueKind::Equiangular
                                                        : TechniqueKind::Connection};
  }
  validateSettings(o.settings);
}

std::string biasInjectionWarning(const RenderSettings& s) {
  if (!s.injectBias || s.integrator == IntegratorKind::Pt) return "";
  return fmt::format("technique {} is multiplied by {:g} (--inject-bias): this image is deliberately wrong",
                     techniqueLabel(s.injectBias->technique()), s.injectBias->factor);
}

void printWarnings(std::ostream& log, const Scene& scene, const RenderSettings& settings) {
  validateSettingsForScene(settings, scene);  // a refusal, before any rendering
  for (const std::string& w : scene.warnings()) log << "pathlab: warning: " << w << "\n";
  if (const std::string w = misOffWarning(scene, settings); !w.empty()) log << "pathlab: warning: " << w << "\n";
  if (const std::string w = mediumSamplingWarning(scene, settings); !w.empty()) log << "pathlab: warning: " << w << "\n";
  if (const std::string w = biasInjectionWarning(settings); !w.empty()) log << "pathlab: warning: " << w << "\n";
}

}  // namespace pathlab::app
