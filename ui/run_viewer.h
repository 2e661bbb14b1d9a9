// Entry point of `pathlab view`: opens the window (or the headless EGL context), runs the viewer
// until it is closed (or for the requested frames) and writes the headless screenshot. The one
// header of ui/ that app/ includes (tests/app_layering_test.py): ViewerOptions and
// checkViewerOptions come with it.
#pragma once

#include "ui/viewer_options.h"

namespace pathlab::ui {

// Returns the process exit code; errors (scene, presets, no display, screenshot path) are
// exceptions with one-line messages.
int runViewer(const ViewerOptions& options);

}  // namespace pathlab::ui
