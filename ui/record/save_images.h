// Saving the shown images (Ctrl+S): side A's as EXR (radiance) and PNG (as displayed), and side
// B's beside it while comparing, in out/ under a fresh name.
#pragma once

#include "ui/lane/render_lane.h"
#include "ui/message_line.h"

namespace pathlab::ui {

// Nothing before A's first full-resolution pass; the message line says what was written or why not.
void saveImages(const RenderLane& a, const RenderLane& b, float exposure, MessageLine& message);

}  // namespace pathlab::ui
