// The cache key of a rendered reference image: the same scene file, settings and budget give the
// same key, so `pathlab converge` without --reference renders a reference once and reuses it.
#pragma once

#include "core/render/render_settings.h"

#include <string>

namespace pathlab {

// 16 hex digits: FNV-1a (64 bit) over the scene file's bytes, every setting that changes the
// estimate (RenderSettings, written out field by field) and the budget text ("time=20" or
// "spp=1024"). Throws std::runtime_error naming the file if it cannot be read. Only the scene file
// itself is hashed: a .gltf whose buffers or textures live in separate files is not re-rendered
// when only those change (the bundled scenes embed everything).
std::string referenceKey(const std::string& scenePath, const RenderSettings& settings, const std::string& budget);

}  // namespace pathlab
