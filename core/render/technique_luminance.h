// The technique maps' input read from a render session's technique pyramid.
#pragma once

#include "core/maps/technique_maps.h"
#include "core/render/render_session.h"

namespace pathlab {

// Every technique up to `length` (0 or more than the pyramid's: the session's pyramid length):
// weighted luminance, and the sampleable luminance when the session keeps it
// (settings.techniqueMaps). Empty without a pyramid.
TechniqueLuminance techniqueLuminance(const RenderSession& session, int length = 0);

// The variance maps' input (settings.varianceMaps): `weighted` holds each technique's variance
// of one pass's estimate (RenderSession::techniqueVariance) instead of its estimate, so that
// dominantMap gives the technique with the most variance and its share of the sum, and
// `image()` the sum of the techniques' variances. No sampleable part.
TechniqueLuminance techniqueVariance(const RenderSession& session, int length = 0);

}  // namespace pathlab
