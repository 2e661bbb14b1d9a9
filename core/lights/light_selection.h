// How next-event estimation chooses a light: in proportion to power everywhere, or by a light
// BVH's importance at the receiver (light_bvh.h). Auto: the BVH when the scene has more than one
// emitter, power otherwise. Light subpaths always start by power.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace pathlab {

enum class LightSelection : uint8_t { Auto, Power, Bvh };

const char* lightSelectionName(LightSelection selection);
// "auto", "power" or "bvh"; nullopt for anything else.
std::optional<LightSelection> parseLightSelection(std::string_view text);

}  // namespace pathlab
