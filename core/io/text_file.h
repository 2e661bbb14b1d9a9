// Text outputs (converge's CSV, SVG and table, the inspector's JSON) written as images are
// (core/film/image_io.h): a temporary beside the target, then a rename, so a reader never sees
// half a file and an interrupted run leaves the old one.
#pragma once

#include <string>

namespace pathlab {

// Throws std::runtime_error naming the file when it cannot be written.
void writeTextAtomically(const std::string& path, const std::string& text);

}  // namespace pathlab
