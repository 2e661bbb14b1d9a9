// GLSL programs from the sources in shaders/, which the build embeds in the binary (so the viewer
// runs from any directory and an installed binary needs no data files). Setting the environment
// variable PATHLAB_SHADER_DIR reads them from that directory instead, to edit shaders live.
#pragma once

#include <string>

namespace pathlab::ui {

// The source of shaders/NAME (embedded, or from $PATHLAB_SHADER_DIR). Throws std::runtime_error
// for an unknown name or an unreadable file.
std::string shaderSource(const std::string& name);

class ShaderProgram {
 public:
  // Compiles and links; throws std::runtime_error with the shader's info log on failure.
  ShaderProgram(const std::string& vertexName, const std::string& fragmentName);
  ~ShaderProgram();
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  unsigned id() const { return program_; }
  int uniform(const char* name) const;

 private:
  unsigned program_ = 0;
};

}  // namespace pathlab::ui
