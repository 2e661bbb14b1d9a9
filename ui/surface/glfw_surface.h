// The viewer's window: GLFW 3.3, an OpenGL 3.3 core context, Dear ImGui's GLFW backend, and file
// drops.
#pragma once

#include "ui/surface/surface.h"

struct GLFWwindow;

namespace pathlab::ui {

class GlfwSurface : public Surface {
 public:
  // Needs an ImGui context. Throws std::runtime_error when no window can be opened (no display).
  GlfwSurface(int width, int height, const std::string& title);
  ~GlfwSurface() override;
  bool waitEvents(double timeoutSeconds) override;
  void newFrame() override;
  void present() override;
  Vec2i framebufferSize() const override;
  void resize(Vec2i size) override;
  bool shouldClose() const override;
  void requestClose() override;
  std::vector<std::string> takeDroppedPaths() override;
  float contentScale() const override;
  bool headless() const override { return false; }

 private:
  GLFWwindow* window_ = nullptr;
  std::vector<std::string> dropped_;
  bool activity_ = true;
  static void onDrop(GLFWwindow* window, int count, const char** paths);
  void installActivityCallbacks();
  static void markActivity(GLFWwindow* window);
};

}  // namespace pathlab::ui
