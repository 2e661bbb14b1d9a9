// Output paths checked before any work. Every output is written as a temporary file in the
// target's directory and then renamed over the target (core/film/image_io.cpp, converge's text
// files, the viewer's screenshot and error CSV), so a target can be written when its directory
// exists, may be written and searched, lies on a file system that holds ordinary files, and the
// target itself is absent or a regular file.
#pragma once

#include "ui/record/output_names.h"

#include <string>

namespace pathlab::app {

// Throws std::runtime_error, one line "PATH: PROBLEM", when `path` cannot be written that way.
// Creates nothing; whether an existing file may be replaced is the caller's policy (--force).
void checkOutputWritable(const std::string& path);
// The same for a directory pathlab creates when it is missing (converge -o): an existing
// directory that may be written, or else a parent in which it may be created.
void checkOutputDirectory(const std::string& dir);
// Text files are written like images (ui/record/output_names.h).
using ui::writeTextAtomically;

}  // namespace pathlab::app
