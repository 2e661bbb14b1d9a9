// The command line the executable builds (app/cli.h), fresh for each test: CLI11 keeps the
// results of a parse.
#pragma once

#include "app/cli.h"

#include <vector>

namespace pathlab::app {

struct TestCli {
  CLI::App app;
  CliOptions options;
  TestCli() { addCommands(app, options); }
  std::vector<CLI::App*> subcommands() {
    return app.get_subcommands([](CLI::App*) { return true; });
  }
};

}  // namespace pathlab::app
