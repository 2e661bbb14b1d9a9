// GLFW window with an OpenGL 3.3 core context driven by Dear ImGui's GLFW backend.
#include "ui/surface/glfw_surface.h"

#include "ui/gl/gl.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace pathlab::ui {

namespace {

std::string lastGlfwError;

void onGlfwError(int, const char* description) { lastGlfwError = description; }

}  // namespace

GlfwSurface::GlfwSurface(int width, int height, const std::string& title) {
  glfwSetErrorCallback(onGlfwError);
  if (!glfwInit())
    throw std::runtime_error("cannot open a window (" + lastGlfwError + "); without a display, use --headless");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot create an OpenGL 3.3 window: " + lastGlfwError);
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  glfwSetWindowUserPointer(window_, this);
  glfwSetDropCallback(window_, onDrop);
  installActivityCallbacks();
  // After our callbacks, so the backend chains to them.
  ImGui_ImplGlfw_InitForOpenGL(window_, true);
}

GlfwSurface::~GlfwSurface() {
  ImGui_ImplGlfw_Shutdown();
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void GlfwSurface::onDrop(GLFWwindow* window, int count, const char** paths) {
  auto* self = static_cast<GlfwSurface*>(glfwGetWindowUserPointer(window));
  for (int i = 0; i < count; ++i) self->dropped_.emplace_back(paths[i]);
  self->activity_ = true;
}

void GlfwSurface::markActivity(GLFWwindow* window) {
  static_cast<GlfwSurface*>(glfwGetWindowUserPointer(window))->activity_ = true;
}

// Every input or window event marks activity: the frame loop draws only then (and when a new
// image arrives), so an idle viewer leaves the CPU to the render threads.
void GlfwSurface::installActivityCallbacks() {
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double, double) { markActivity(w); });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int, int, int) { markActivity(w); });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double) { markActivity(w); });
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int, int, int, int) { markActivity(w); });
  glfwSetCharCallback(window_, [](GLFWwindow* w, unsigned) { markActivity(w); });
  glfwSetCursorEnterCallback(window_, [](GLFWwindow* w, int) { markActivity(w); });
  glfwSetWindowFocusCallback(window_, [](GLFWwindow* w, int) { markActivity(w); });
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { markActivity(w); });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { markActivity(w); });
}

bool GlfwSurface::waitEvents(double timeoutSeconds) {
  if (timeoutSeconds > 0.0) glfwWaitEventsTimeout(timeoutSeconds);
  else glfwPollEvents();
  return std::exchange(activity_, false);
}

void GlfwSurface::newFrame() { ImGui_ImplGlfw_NewFrame(); }

void GlfwSurface::present() { glfwSwapBuffers(window_); }

Vec2i GlfwSurface::framebufferSize() const {
  Vec2i size;
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

void GlfwSurface::resize(Vec2i size) { glfwSetWindowSize(window_, std::max(size.x, 1), std::max(size.y, 1)); }

bool GlfwSurface::shouldClose() const { return glfwWindowShouldClose(window_); }
void GlfwSurface::requestClose() { glfwSetWindowShouldClose(window_, GLFW_TRUE); }

std::vector<std::string> GlfwSurface::takeDroppedPaths() { return std::exchange(dropped_, {}); }

float GlfwSurface::contentScale() const {
  float x = 1.f, y = 1.f;
  glfwGetWindowContentScale(window_, &x, &y);
  return std::max(x, 1.f);
}

}  // namespace pathlab::ui
