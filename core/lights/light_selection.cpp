// LightSelection's names, as --light-sampler and the viewer's script take them.
#include "core/lights/light_selection.h"

namespace pathlab {

const char* lightSelectionName(LightSelection selection) {
  switch (selection) {
    case LightSelection::Auto: return "auto";
    case LightSelection::Power: return "power";
    case LightSelection::Bvh: return "bvh";
  }
  return "?";
}

std::optional<LightSelection> parseLightSelection(std::string_view text) {
  for (const LightSelection s : {LightSelection::Auto, LightSelection::Power, LightSelection::Bvh})
    if (text == lightSelectionName(s)) return s;
  return std::nullopt;
}

}  // namespace pathlab
