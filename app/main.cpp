// pathlab: one executable, subcommands wired to the core. Every error becomes one line and exit 1.
#include "app/cli.h"

#include <exception>
#include <iostream>

int main(int argc, char** argv) {
  CLI::App app{"pathlab: a bidirectional path tracer for studying the path integral formulation of light transport"};
  app.require_subcommand(1);
  // One line per error, as for every other failure (CLI11's default adds a second line).
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return "pathlab: " + std::string(e.what()) + "\n"; });
  pathlab::app::CliOptions options;
  pathlab::app::addCommands(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    if (app.got_subcommand("render")) return pathlab::app::runRender(options.render);
    if (app.got_subcommand("converge")) return pathlab::app::runConverge(options.converge);
    if (app.got_subcommand("view")) return pathlab::app::runView(options.view);
    if (app.got_subcommand("check")) return pathlab::app::runCheck(options.check);
    if (app.got_subcommand("inspect")) return pathlab::app::runInspect(options.inspect);
  } catch (const std::exception& e) {
    std::cerr << "pathlab: " << e.what() << "\n";
    return 1;
  }
  return 1;
}
