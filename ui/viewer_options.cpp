// The checks of `pathlab view`'s options that need neither the scene nor a window.
#include "ui/viewer_options.h"

#include "ui/lane/compare.h"
#include "ui/estimator/technique_map_view.h"
#include "ui/inspect/outlier_list.h"

#include <stdexcept>

namespace pathlab::ui {

void checkViewerOptions(const ViewerOptions& o) {
  if (!o.techniqueMap.empty()) {
    parseMapView(o.techniqueMap);
    if (o.settings.integrator == IntegratorKind::Pt)
      throw std::runtime_error("--technique-map needs the bidirectional tracer (--integrator bpt or lt)");
  }
  if (!o.compare.empty()) compareEstimator(o.compare, o.settings);
  if (o.outliers > 0) {
    if (const std::string problem = outlierFinderProblem(o.settings); !problem.empty())
      throw std::runtime_error("--outliers: " + problem);
  }
}

}  // namespace pathlab::ui
