// The cache key of a rendered reference image: the same scene file, settings and budget give the
// same key, so `pathlab converge` without --reference renders a reference once and reuses it.
#pragma once

#include "core/render/render_settings.h"

#include <string>

namespace pathlab {

// 16 hex digits: FNV-1a (64 bit) over the scene file's bytes, the bytes of every external file the
// glTF loader reads for it (buffers such as a .gltf's .bin, and image files, found exactly as the
// loader finds them: tinygltf resolves and reads them, the key hashes what it read), every setting
// that changes the estimate (RenderSettings, written out field by field) and the budget text
// ("time=20" or "spp=1024"). Only contents are hashed, not paths: the same scene in another
// directory gives the same key; a scene whose buffers and images are embedded keeps the key it
// had before external files were hashed. Throws std::runtime_error naming the file if the scene
// or one of its external files cannot be read (call it on a scene that loads).
std::string referenceKey(const std::string& scenePath, const RenderSettings& settings, const std::string& budget);

}  // namespace pathlab
