// EGL surfaceless context + framebuffer object (the recipe verified in ../shared/TOOLCHAIN.md).
#include "ui/surface/egl_surface.h"

#include "ui/gl/gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <imgui.h>

#include <stdexcept>
#include <string>

namespace pathlab::ui {

namespace {

[[noreturn]] void fail(const std::string& step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", eglGetError());
  throw std::runtime_error("headless OpenGL (EGL surfaceless): " + step + " failed (EGL error " + code + ")");
}

}  // namespace

EglSurface::EglSurface(int width, int height) : size_(width, height) {
  auto getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay) fail("eglGetPlatformDisplayEXT lookup");
  EGLDisplay dpy = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (dpy == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
  if (!eglInitialize(dpy, nullptr, nullptr)) fail("eglInitialize");
  display_ = dpy;
  if (!eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
  // Without EGL_PBUFFER_BIT no config matches on Mesa's surfaceless platform.
  const EGLint configAttribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                  EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_NONE};
  EGLConfig config;
  EGLint count = 0;
  if (!eglChooseConfig(dpy, configAttribs, &config, 1, &count) || count < 1) fail("eglChooseConfig");
  const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                   EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext ctx = eglCreateContext(dpy, config, EGL_NO_CONTEXT, contextAttribs);
  if (ctx == EGL_NO_CONTEXT) fail("eglCreateContext (OpenGL 3.3 core)");
  context_ = ctx;
  if (!eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx)) fail("eglMakeCurrent");

  glGenFramebuffers(1, &framebuffer_);
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("headless OpenGL: the offscreen framebuffer is incomplete");
}

EglSurface::~EglSurface() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteRenderbuffers(1, &colour_);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

void EglSurface::newFrame() {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(size_.x), static_cast<float>(size_.y));
  io.DisplayFramebufferScale = ImVec2(1.f, 1.f);
  const auto now = std::chrono::steady_clock::now();
  io.DeltaTime = std::max(std::chrono::duration<float>(now - last_).count(), 1e-4f);
  last_ = now;
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
}

void EglSurface::present() { glFinish(); }

void EglSurface::resize(Vec2i size) {
  size_ = glm::max(size, Vec2i(1));
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size_.x, size_.y);
}

}  // namespace pathlab::ui
