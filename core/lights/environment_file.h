// Reading an environment from the command line's words: an equirectangular map (.exr through
// tinyexr, .hdr through stb_image) or a constant radiance "R,G,B".
#pragma once

#include "core/lights/environment_desc.h"

#include <stdexcept>
#include <string>

namespace pathlab {

// One line naming the file (or the text) and the problem.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `spec` is FILE.exr, FILE.hdr or R,G,B (three finite non-negative numbers). Strength and
// rotation are the caller's to set.
EnvironmentDesc readEnvironment(const std::string& spec);

}  // namespace pathlab
