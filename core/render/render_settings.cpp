// Names of the settings' enumerations, as the CLI and the viewer print them.
#include "core/render/render_settings.h"

namespace pathlab {

const char* integratorName(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::Pt: return "pt";
    case IntegratorKind::Bpt: return "bpt";
    case IntegratorKind::Lt: return "lt";
  }
  return "?";
}

}  // namespace pathlab
