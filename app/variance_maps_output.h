// `render --variance-maps L` output (issue 34, "where the noise comes from"): per technique up to
// length L, the variance of one pass's estimate of each pixel by that technique alone
// (TechniqueFilms::readoutVariance), and the dominant variance map (per pixel, the technique with
// the most variance and its share of the techniques' sum), as EXR (the numbers) and PNG (a
// labelled mosaic on a log scale, and the dominant map with its legend) next to the output.
#pragma once

#include "core/render/render_session.h"

#include <string>
#include <vector>

namespace pathlab::app {

// Every file the variance maps of length L write next to `output` (OUT.ext -> OUT-variance-s0-t2.exr,
// ..., OUT-variance.png, OUT-variance-dominant.exr, OUT-variance-dominant.png; merges, when
// `families` has them, as OUT-variance-m-s2-t2.exr).
std::vector<std::string> varianceMapPaths(const std::string& output, int length,
                                          TechniqueFamilies families = TechniqueFamilies::Connections);
// The session must keep the moments (settings.varianceMaps, pyramid length >= length).
void writeVarianceMaps(const std::string& output, const RenderSession& session, int length);

}  // namespace pathlab::app
