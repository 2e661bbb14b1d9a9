// `pathlab check`: the consistency check of the bidirectional techniques (issue 13, part 4).
#pragma once

#include "app/estimator_options.h"
#include "app/shared_options.h"
#include "core/check/check_report.h"
#include "core/check/merge_bias.h"
#include "core/scene/scene.h"

#include <nlohmann/json.hpp>

#include <atomic>
#include <optional>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include <string>

namespace pathlab::app {

struct CheckCommandOptions {
  SceneOptions scene;
  EstimatorOptions estimator = [] {
    EstimatorOptions e;
    e.settings.checkTechniques = true;
    // With merges, each radius of the ladder is rendered fixed (alpha = 1; merge_bias.h).
    e.settings.mergeRadiusAlpha = 1.f;
    return e;
  }();
  // Not given: the camera's shape with the longest side 128 (the check needs passes, not pixels).
  ImageSizeOptions size;
  SampleBudget budget;   // neither given: the default time
  int threads = 0;
  CheckOptions check;
  // With merges: the radii r, r/2, ..., r/2^(levels-1), r from --radius (merge_bias.h).
  int radiusLevels = 3;
  std::string json;  // also write the verdict as JSON here
  bool force = false;
};

void addCheckCommand(CLI::App& app, CheckCommandOptions& options);
// The options of check but the scene, --json and --force, registered on `cmd` (check's, and the
// Python module's pathlab.check).
void addCheckOptions(CLI::App* cmd, CheckCommandOptions& options);
// Exit code 0 when every compared technique agrees, 1 when one disagrees (errors: exceptions).
int runCheck(CheckCommandOptions options);

// What a check found: the verdicts of the connections and, with merges, of each merge's bias.
struct CheckOutcome {
  RenderSettings settings;  // as rendered (the first radius's, with the image size)
  int radiusLevels = 1;
  CheckReport report;
  std::optional<MergeBiasReport> merges;
  bool agrees() const { return report.agrees() && (!merges || merges->agrees()); }
};
// The estimator options checked (finishEstimatorOptions and check's own refusals); throws the
// command line's one-line messages.
void finishCheckOptions(CheckCommandOptions& options);
// The check's renders of `scene` (one, or one per radius) and their verdicts; `progress`: a
// progress bar on stderr. `stop`, when set (from any thread), ends the check after the pass in
// progress by throwing CheckStopped (the Python module's Ctrl+C).
class CheckStopped : public std::runtime_error {
 public:
  CheckStopped() : std::runtime_error("the check was stopped") {}
};
CheckOutcome checkScene(CheckCommandOptions& options, const Scene& scene, bool progress,
                        const std::atomic<bool>* stop = nullptr);
// The JSON of check --json.
nlohmann::json checkOutcomeJson(const CheckOutcome& outcome, const std::string& scenePath);

}  // namespace pathlab::app
