// The technique maps' input read from a render session's technique pyramid.
#pragma once

#include "core/maps/technique_maps.h"
#include "core/render/render_session.h"

namespace pathlab {

// Every technique up to `length` (0 or more than the pyramid's: the session's pyramid length):
// weighted luminance, the sampleable luminance when the session keeps it (settings.techniqueMaps)
// and the variance of a pass's estimate when it keeps that (settings.varianceMaps). Empty without
// a pyramid.
TechniqueLuminance techniqueLuminance(const RenderSession& session, int length = 0);

}  // namespace pathlab
