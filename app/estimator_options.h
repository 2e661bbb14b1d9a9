// The options that change the estimate, shared by `render` and `view` so a demo starts in the
// same state a headless render would: integrator, MIS, techniques, isolation, pyramid, length.
#pragma once

#include "core/render/render_settings.h"
#include "core/scene/scene.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <ostream>
#include <string>

namespace pathlab::app {

struct EstimatorOptions {
  // The CLI renders bidirectionally unless told otherwise (--integrator pt).
  RenderSettings settings = [] {
    RenderSettings s;
    s.integrator = IntegratorKind::Bpt;
    return s;
  }();
  // --integrator as typed: pt, bpt, lt, or vcm / bpm (bpt with the merges: every connection and
  // every merge, or the merges alone, Georgiev et al. 2012's vertex connection and merging and
  // bidirectional photon mapping), which set the techniques.
  std::string integrator = "bpt";
  std::string techniques;  // a TechniqueSet SPEC; empty: the integrator's own ("all" for bpt)
  std::string isolate;      // "S,T" or empty
  bool unweighted = false;  // with --isolate
  std::string injectBias;   // "S,T,FACTOR" or empty
  // Metropolis (--integrator mlt): given or not, so that another integrator refuses them.
  std::optional<std::string> mltVariant;
  std::optional<int> chains;
  std::optional<uint64_t> bootstrap;
  std::optional<float> largeStep, sigma;
  std::optional<int> mltDirect;
};

// Registers --max-length --integrator --mis --connect --beta --min-connection --techniques --isolate --unweighted --rr/--no-rr
// --seed --aperture --focus-distance --inject-bias on `cmd`.
void addEstimatorOptions(CLI::App* cmd, EstimatorOptions& options);
// Turns the parsed strings into settings.techniques and settings.isolate and checks the result with validateSettings
// (throws one-line std::invalid_argument / std::runtime_error messages naming the option).
void finishEstimatorOptions(EstimatorOptions& options);
// The one-line warning of --inject-bias for these settings, "" without one.
std::string biasInjectionWarning(const RenderSettings& settings);
// The scene's warnings, then those of the settings on it (--mis off, --inject-bias), a line each.
void printWarnings(std::ostream& log, const Scene& scene, const RenderSettings& settings);

}  // namespace pathlab::app
