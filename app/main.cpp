// pathlab: one executable, subcommands wired to the core. Every error becomes one line and exit 1.
// Started by an MPI launcher (mpirun, srun), `render` and `converge` run as one rank of the job (app/job.h).
#include "app/cli.h"
#include "app/job.h"
#ifdef PATHLAB_HAVE_MPI
#include "app/mpi_job.h"
#endif

#include <exception>
#include <iostream>
#include <memory>
#include <sstream>

int main(int argc, char** argv) {
  std::unique_ptr<pathlab::app::Job> job;
#ifdef PATHLAB_HAVE_MPI
  job = pathlab::app::MpiJob::startIfLaunched(&argc, &argv);
#endif
  if (!job) job = std::make_unique<pathlab::app::Job>();

  CLI::App app{"pathlab: a bidirectional path tracer for studying the path integral formulation of light transport"};
  app.require_subcommand(1);
  // One line per error, as for every other failure (CLI11's default adds a second line).
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return "pathlab: " + std::string(e.what()) + "\n"; });
  pathlab::app::CliOptions options;
  pathlab::app::addCommands(app, options);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // Every rank parsed the same command line: the leader alone says what is wrong (or --help).
    if (job->leader()) return app.exit(e);
    std::ostringstream discard;
    return app.exit(e, discard, discard);
  }
  try {
    if (app.got_subcommand("render")) return pathlab::app::runRender(options.render, *job);
    if (app.got_subcommand("converge")) return pathlab::app::runConverge(options.converge, *job);
    if (job->size() > 1)
      throw pathlab::app::JobStopped(job->leader() ? "only render and converge run as an MPI job: start " +
                                                         app.get_subcommands().front()->get_name() +
                                                         " as one process, without mpirun"
                                                   : "");
    if (app.got_subcommand("view")) return pathlab::app::runView(options.view);
    if (app.got_subcommand("check")) return pathlab::app::runCheck(options.check);
    if (app.got_subcommand("inspect")) return pathlab::app::runInspect(options.inspect);
    if (app.got_subcommand("outliers")) return pathlab::app::runOutliers(options.outliers);
    if (app.got_subcommand("make-volume")) return pathlab::app::runMakeVolume(options.makeVolume);
  } catch (const pathlab::app::JobStopped& e) {
    // Every rank stops together (Job::agree); the leader's line says why.
    if (*e.what()) std::cerr << "pathlab: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    if (job->size() == 1) {
      std::cerr << "pathlab: " << e.what() << "\n";
      return 1;
    }
    // One rank failed while the others may wait for it in a collective: end the whole job.
    std::cerr << "pathlab: rank " << job->rank() << " of " << job->size() << ": " << e.what() << "\n" << std::flush;
    job->abort(1);
    return 1;
  }
  return 1;
}
