// OpenGL without a loader: glvnd's libOpenGL exports every GL 4.5 entry point and dispatches to
// whichever context (GLX or EGL) is current, so prototypes are enough (GLEW fails under EGL).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/gl.h>
#include <GL/glext.h>
