// Names for files the viewer writes on request: never an existing file (the user's work is not
// overwritten without asking, as for `pathlab render`).
#pragma once

#include "core/io/text_file.h"  // writeTextAtomically, for the files the viewer writes

#include <string>
#include <vector>

namespace pathlab::ui {

// "DIR/PREFIX-YYYYMMDD-HHMMSS" (local time), with "-2", "-3", ... appended until no file
// DIR/STEM.EXT exists for any of `extensions` (e.g. {".exr", ".png"}). Creates DIR if missing.
std::string freshStem(const std::string& dir, const std::string& prefix, const std::vector<std::string>& extensions);

}  // namespace pathlab::ui
