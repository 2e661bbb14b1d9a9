// Every subcommand on one App, and the finite check applied to every numeric option.
#include "app/cli.h"

namespace pathlab::app {

void addCommands(CLI::App& app, CliOptions& o) {
  addRenderCommand(app, o.render);
  addConvergeCommand(app, o.converge);
  addViewCommand(app, o.view);
  addCheckCommand(app, o.check);
  addInspectCommand(app, o.inspect);
  addOutliersCommand(app, o.outliers);
  addMakeVolumeCommand(app, o.makeVolume);
  requireFiniteNumbers(app);
}

}  // namespace pathlab::app
