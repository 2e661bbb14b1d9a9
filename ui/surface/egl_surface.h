// Headless drawing for CI and screenshots: an EGL surfaceless context on Mesa (llvmpipe, no
// display, no GPU; ../shared/TOOLCHAIN.md) rendering into an offscreen framebuffer object.
#pragma once

#include "ui/surface/surface.h"

#include <chrono>

namespace pathlab::ui {

class EglSurface : public Surface {
 public:
  // Needs an ImGui context. Throws std::runtime_error naming the failing EGL step.
  EglSurface(int width, int height);
  ~EglSurface() override;
  bool waitEvents(double) override { return true; }
  void newFrame() override;
  void present() override;
  Vec2i framebufferSize() const override { return size_; }
  void resize(Vec2i size) override;
  bool shouldClose() const override { return closed_; }
  void requestClose() override { closed_ = true; }
  bool headless() const override { return true; }

 private:
  Vec2i size_;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  unsigned framebuffer_ = 0, colour_ = 0;
  bool closed_ = false;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace pathlab::ui
