// Scene values converted to the 32-bit floats the renderer computes with, checked after the
// conversion: a double can be finite where its float is not.
#include "core/scene/gltf_internal.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace pathlab::gltf {

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(6);
  out << value;
  return out.str();
}

std::string overflowText() {
  return "overflows a 32-bit float (largest " +
         formatNumber(double(std::numeric_limits<float>::max())) + ")";
}

float toFiniteFloat(double value, const std::string& what) {
  if (!std::isfinite(value)) {
    throw LoadError(what + " " + formatNumber(value) + " is not a finite number");
  }
  const float f = float(value);
  if (!std::isfinite(f)) throw LoadError(what + " " + formatNumber(value) + " " + overflowText());
  return f;
}

}  // namespace pathlab::gltf
