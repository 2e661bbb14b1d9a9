// Where the viewer draws: a GLFW window on a display, or an EGL surfaceless context with an
// offscreen framebuffer (headless: no display, no GPU). Each owns its GL context and feeds
// Dear ImGui's platform side (display size, time step, input).
#pragma once

#include "core/math/types.h"

#include <string>
#include <vector>

namespace pathlab::ui {

class Surface {
 public:
  virtual ~Surface() = default;
  // Processes pending events, waiting up to `timeoutSeconds` for one; returns whether any input
  // or window event arrived since the last call (offscreen: always true, every frame is drawn).
  virtual bool waitEvents(double timeoutSeconds) = 0;
  // Starts the ImGui platform frame (io.DisplaySize, io.DeltaTime, input).
  virtual void newFrame() = 0;
  // Shows the frame (window) or finishes it (offscreen). Bound framebuffer is the one to read.
  virtual void present() = 0;
  virtual Vec2i framebufferSize() const = 0;
  // Asks for a new size in window pixels (a user's resize, or a test's).
  virtual void resize(Vec2i size) = 0;
  virtual bool shouldClose() const = 0;
  virtual void requestClose() = 0;
  // Files dropped on the window since the last call.
  virtual std::vector<std::string> takeDroppedPaths() { return {}; }
  // Display scale factor (HiDPI), 1 offscreen.
  virtual float contentScale() const { return 1.f; }
  virtual bool headless() const = 0;
};

}  // namespace pathlab::ui
