// `render --technique-maps L` output: the dominant technique (every length up to L, and each
// length), each technique's share of the image and where each cannot sample, as EXR (the numbers)
// and PNG (colours with a legend or colour bar) next to the output (core/maps/).
#pragma once

#include "core/render/render_session.h"

#include <string>
#include <vector>

namespace pathlab::app {

// Every file the maps of length L write next to `output` (OUT.ext -> OUT-dominant.exr, .png,
// OUT-dominant-k1.exr, ..., OUT-share-s0-t2.exr, ..., OUT-share.png, OUT-cannot-s0-t2.exr, ...,
// OUT-cannot-sample.png).
// Merges (when `families` has them) as OUT-share-m-s2-t2.exr, ..., and the share of every merge
// together, OUT-share-merges.exr and .png.
std::vector<std::string> techniqueMapPaths(const std::string& output, int length,
                                           TechniqueFamilies families = TechniqueFamilies::Connections);
// The session must keep the maps' films (settings.techniqueMaps, pyramid length >= length).
void writeTechniqueMaps(const std::string& output, const RenderSession& session, int length);

}  // namespace pathlab::app
