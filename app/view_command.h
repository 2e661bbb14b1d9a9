// `pathlab view`: the interactive viewer's options (the estimator options are render's).
#pragma once

#include "app/environment_options.h"
#include "app/estimator_options.h"
#include "ui/run_viewer.h"  // app/'s one entry into ui/

#include <CLI/CLI.hpp>

namespace pathlab::app {

struct ViewOptions {
  EstimatorOptions estimator;
  ui::ViewerOptions viewer;
  EnvironmentOptions environment;  // into viewer.load before the scene loads
  std::string zMap;  // --z-map S,T
};

void addViewCommand(CLI::App& app, ViewOptions& options);
// Returns the process exit code. Errors are exceptions, reported by main.
int runView(ViewOptions options);

}  // namespace pathlab::app
